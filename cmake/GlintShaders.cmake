# glint_add_shaders(TARGET name SOURCES a.vert b.frag ...)
# Compiles each GLSL file to SPIR-V with glslangValidator at build time into a C header
# holding a uint32_t array (--vn), tracked through the compiler's depfile, and builds a
# static library exposing glint::spirv(ShaderId). No .spv file exists at run time.
function(glint_add_shaders)
  cmake_parse_arguments(S "" "TARGET" "SOURCES" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${out_dir})
  set(headers)
  set(ids)
  set(cases)
  set(includes)
  foreach(src ${S_SOURCES})
    get_filename_component(name ${src} NAME)
    string(REPLACE "." "_" symbol "glint_spv_${name}")
    set(header ${out_dir}/${name}.h)
    set(debug_flag)
    if(GLINT_SHADER_DEBUG)
      set(debug_flag -g)
    endif()
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLINT_GLSLANG} -V --target-env vulkan1.2 ${debug_flag}
              -I${CMAKE_CURRENT_SOURCE_DIR} --vn ${symbol}
              --depfile ${header}.d -o ${header} ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      DEPFILE ${header}.d
      COMMENT "glslang ${src}"
      VERBATIM)
    list(APPEND headers ${header})
    string(REPLACE "." "_" id "${name}")
    list(APPEND ids "    ${id},")
    list(APPEND includes "#include \"spirv/${name}.h\"")
    # note: string(APPEND), not list(APPEND): the ';' ending the statement would split a list.
    string(APPEND cases "    case ShaderId::${id}: return {${symbol}, sizeof(${symbol}) / sizeof(uint32_t)};\n")
  endforeach()
  list(JOIN ids "\n" ids)
  list(JOIN includes "\n" includes)
  # Headers shared by GLSL and C++ (shaders/bindings.h) are copied next to the generated
  # ones, so C++ includes them as "spirv/bindings.h" (render may use spirv/, not shaders/).
  file(GLOB shared_headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.h)
  foreach(h ${shared_headers})
    get_filename_component(hname ${h} NAME)
    configure_file(${h} ${out_dir}/${hname} COPYONLY)
  endforeach()
  configure_file(${PROJECT_SOURCE_DIR}/cmake/shader_ids.h.in ${out_dir}/shader_ids.h @ONLY)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/shader_lookup.cpp.in ${out_dir}/shader_lookup.cpp @ONLY)
  add_library(${S_TARGET} STATIC ${out_dir}/shader_lookup.cpp ${headers})
  target_include_directories(${S_TARGET} PUBLIC ${CMAKE_CURRENT_BINARY_DIR} ${PROJECT_SOURCE_DIR})
  target_link_libraries(${S_TARGET} PRIVATE glint_options)
endfunction()
