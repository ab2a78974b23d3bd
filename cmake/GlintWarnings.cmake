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
endfunction()
