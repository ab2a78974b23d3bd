# glint_warnings: the warning set every glint target builds with.
add_library(glint_warnings INTERFACE)
target_compile_options(glint_warnings INTERFACE -Wall -Wextra -Wshadow -Wconversion
  # note: STYLE.md asks for designated initializers that name only the fields that differ
  # from their defaults (Options{.max_iterations = 50}); GCC's -Wextra flags every such call.
  -Wno-missing-field-initializers)
if(GLINT_WERROR)
  target_compile_options(glint_warnings INTERFACE -Werror)
endif()

# glint_options: sanitizers and other whole-build switches, linked by every target.
add_library(glint_options INTERFACE)
if(GLINT_SANITIZE)
  target_compile_options(glint_options INTERFACE -fsanitize=address,undefined
                                                 -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(glint_options INTERFACE -fsanitize=address,undefined)
endif()
if(GLINT_FUZZ)
  # note: coverage instrumentation for libFuzzer on every library; the harnesses in fuzz/
  # add -fsanitize=fuzzer at link time (libFuzzer's main).
  target_compile_options(glint_options INTERFACE -fsanitize=fuzzer-no-link,address,undefined
                                                 -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(glint_options INTERFACE -fsanitize=address,undefined)
endif()

# glint_module(NAME sources...): a library target glint_NAME with the repo root as include root.
function(glint_module name)
  add_library(glint_${name} ${ARGN})
  target_include_directories(glint_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(glint_${name} PRIVATE glint_warnings PUBLIC glint_options)
  glint_unity(glint_${name})
endfunction()

# glint_unity(TARGET): with GLINT_UNITY, TARGET compiles as unity translation units.
function(glint_unity target)
  if(GLINT_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON
      UNITY_BUILD_BATCH_SIZE ${GLINT_UNITY_BATCH})
  endif()
endfunction()

# glint_plugin(NAME MODULE_OF sources...): the plugin glint_NAME (libglint_NAME.so), opened by
# module glint_MODULE_OF with dlopen (mesh/plugin_library.h). It links no glint library: a
# second copy of glint_mesh would hold a second set of its process-wide state (the cancel
# flag, the staged-output registry); -z defs proves it when no sanitizer leaves its runtime's
# symbols to the program. Hidden symbols but its one entry; -Bsymbolic: its own inline and
# template code binds inside it, never to a copy the program happens to export. In the build
# tree it sits in lib/glint/, so a program one folder down (tools/glint, python/, fuzz/) finds
# it at ../lib/glint as the installed bin/glint does; whatever links the module gets it built.
function(glint_plugin name module_of)
  add_library(glint_${name} MODULE ${ARGN})
  set_target_properties(glint_${name} PROPERTIES
    LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/lib/glint
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  target_include_directories(glint_${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(glint_${name} PRIVATE glint_warnings glint_options Eigen3::Eigen)
  target_link_options(glint_${name} PRIVATE -Wl,-Bsymbolic)
  if(NOT GLINT_SANITIZE AND NOT GLINT_FUZZ)
    target_link_options(glint_${name} PRIVATE -Wl,-z,defs)
  endif()
  add_dependencies(glint_${module_of} glint_${name})
  include(GNUInstallDirs)
  install(TARGETS glint_${name} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/glint COMPONENT glint)
endfunction()
