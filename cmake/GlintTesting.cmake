include(GoogleTest)

# glint_add_test(NAME SOURCES ... LIBS ... LABELS ...): one GoogleTest executable per module.
function(glint_add_test name)
  cmake_parse_arguments(T "" "" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main glint_warnings)
  target_compile_definitions(${name} PRIVATE
    GLINT_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data"
    GLINT_GOLDEN_DIR="${PROJECT_SOURCE_DIR}/tests/golden"
    GLINT_SHARED_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/data"
    GLINT_TEST_OUTPUT_DIR="${CMAKE_BINARY_DIR}/test-output")
  # note: test programs sit two folders down (tests/<module>/), where the volume plugin's
  # search (volume/detail/volume_plugin.h) would not find the build's lib/glint by itself.
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${T_LABELS}"
    ENVIRONMENT "GLINT_PLUGIN_DIR=${CMAKE_BINARY_DIR}/lib/glint")
endfunction()
