cmake_minimum_required(VERSION 3.25)
# Fails when a file includes a module its folder must not depend on (DESIGN.md, STYLE.md §2):
#
#   mesh ◀ image ◀ render ◀ scanner ◀ decision ◀ analysis ◀ report ◀ scenario ◀ tools, python
#   mesh ◀ registration ◀ analysis        mesh ◀ volume ◀ analysis
#
# An arrow points at what may be used; nothing points back. A module's tests (tests/<module>/)
# may use what the module may use, the module itself and the tests' own helpers; bench/ and
# fuzz/ sit on top like tools/ (fuzz/ may use tools/ too). Run as `cmake -DROOT=<repo> -P check_layering.cmake`; with
# -DEXTRA_FILE=<path> -DEXTRA_MODULE=<module> one more file is checked as if it lay in that
# module (the test that proves an include pointing up fails).
set(allowed_mesh "mesh")
set(allowed_image "mesh;image")
set(allowed_render "mesh;image;render;spirv")
set(allowed_registration "mesh;registration")
set(allowed_volume "mesh;volume")
set(allowed_scanner "mesh;image;render;scanner")
set(allowed_decision "mesh;image;render;scanner;decision")
set(allowed_analysis "mesh;image;render;scanner;decision;registration;volume;analysis")
set(allowed_report "${allowed_analysis};report")
set(allowed_scenario "${allowed_report};scenario")
set(allowed_tools "${allowed_scenario};tools")
set(allowed_python "${allowed_scenario};python")
set(allowed_bench "${allowed_scenario};bench")
# note: fuzz/ may also use tools/: fuzz_render_pick parses command lines with the commands' own
# flags and checks (tools/view_flags.h), which belong to the command line.
set(allowed_fuzz "${allowed_tools};fuzz")
set(modules mesh image render registration volume scanner decision analysis report scenario tools python
    bench fuzz)

set(bad "")
# check_file(<file> <allowed list>): every `#include "module/…"` names an allowed module.
function(check_file f allowed)
  file(STRINGS ${f} lines REGEX "^#include \"[a-z_]+/")
  foreach(line ${lines})
    string(REGEX REPLACE "^#include \"([a-z_]+)/.*" "\\1" used "${line}")
    if(NOT used IN_LIST allowed)
      string(APPEND bad "${f}: ${line} (may use: ${allowed})\n")
    endif()
  endforeach()
  set(bad "${bad}" PARENT_SCOPE)
endfunction()

foreach(module ${modules})
  file(GLOB_RECURSE files ${ROOT}/${module}/*.h ${ROOT}/${module}/*.cpp)
  foreach(f ${files})
    check_file(${f} "${allowed_${module}}")
  endforeach()
  if(IS_DIRECTORY ${ROOT}/tests/${module})
    file(GLOB_RECURSE files ${ROOT}/tests/${module}/*.h ${ROOT}/tests/${module}/*.cpp)
    foreach(f ${files})
      check_file(${f} "${allowed_${module}};tests")
    endforeach()
  endif()
endforeach()
if(DEFINED EXTRA_FILE)
  check_file(${EXTRA_FILE} "${allowed_${EXTRA_MODULE}}")
endif()
if(bad)
  # note: NOTICE prints the lines as they are (FATAL_ERROR would wrap them at 80 columns).
  message(NOTICE "layering violations (an include that points up the chain):\n${bad}")
  message(FATAL_ERROR "layering: see the violations above")
endif()
message(STATUS "layering: ok")
