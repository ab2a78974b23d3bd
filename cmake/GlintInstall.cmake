# `cmake --install` and CPack (.deb).
#
# Installed (prefix-relative):
#   bin/glint                                  the command line: a launcher (tools/launcher) that
#                                              holds SIGINT/SIGTERM and runs lib/glint/glint-program
#   lib/glint/glint-program                    the program (shaders are embedded in it)
#   share/doc/glint/README.md                  how to use it
#   share/glint/scenarios/                     the shipped scenarios (tools/demo runs one)
#   share/glint/workflows/cohort/              the Snakemake cohort workflow
#   share/glint/report/html/glint.css          the page style cohort.html shares with report.html
#   share/glint/slicer/execution-model.xsd     the schema glint --xml is tested against
#   lib/glint/slicer/glint                     link to bin/glint: the folder to add to 3D Slicer's
#                                              module paths (Slicer runs every program there)
#   ${GLINT_PYTHON_INSTALL_DIR}/glint….so      the Python module (component python)
#
# The glint libraries are static, so nothing else of the build is needed at run time; the
# Debian libraries come from their packages (the .deb depends on them, found by
# dpkg-shlibdeps).
include(GNUInstallDirs)

install(TARGETS glint RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT glint)
install(TARGETS glint_program RUNTIME DESTINATION ${CMAKE_INSTALL_LIBDIR}/glint COMPONENT glint)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT glint)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenarios/ DESTINATION ${CMAKE_INSTALL_DATADIR}/glint/scenarios
        COMPONENT glint)
install(FILES ${PROJECT_SOURCE_DIR}/tools/slicer/execution-model.xsd DESTINATION ${CMAKE_INSTALL_DATADIR}/glint/slicer
        COMPONENT glint)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/workflows/ DESTINATION ${CMAKE_INSTALL_DATADIR}/glint/workflows
        COMPONENT glint PATTERN ".snakemake" EXCLUDE PATTERN "__pycache__" EXCLUDE)
# The page style report.html inlines at build time, for the cohort summary's cohort.html: two
# folders above workflows/cohort/, as in the sources (workflows/cohort/summary_html.py).
install(FILES ${PROJECT_SOURCE_DIR}/report/html/glint.css DESTINATION ${CMAKE_INSTALL_DATADIR}/glint/report/html
        COMPONENT glint)
# note: a relative link, so it resolves under any prefix (and inside the .deb).
install(CODE "
  set(slicer_dir \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/glint/slicer\")
  file(MAKE_DIRECTORY \"\${slicer_dir}\")
  file(CREATE_LINK ../../../${CMAKE_INSTALL_BINDIR}/glint \"\${slicer_dir}/glint\" SYMBOLIC)
  message(STATUS \"Installing: \${slicer_dir}/glint -> ../../../${CMAKE_INSTALL_BINDIR}/glint\")"
  COMPONENT glint)

set(CPACK_PACKAGE_NAME glint)
set(CPACK_PACKAGE_VENDOR "glint developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "damage on 3D surfaces by light-reflection analysis (virtual rotary scanner)")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "glint developers <glint@localhost>")
set(CPACK_GENERATOR DEB)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# Runtime libraries: dpkg-shlibdeps reads the ELF files and names the Debian packages (with
# versions) that provide every shared library they load.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_GLINT_PACKAGE_NAME glint)
# Vulkan on the CPU (lavapipe) and its loader; Embree renders without them, so a recommendation.
set(CPACK_DEBIAN_GLINT_PACKAGE_RECOMMENDS "mesa-vulkan-drivers, snakemake")
set(CPACK_COMPONENTS_ALL glint)
if(GLINT_BUILD_PYTHON)
  list(APPEND CPACK_COMPONENTS_ALL python)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-glint)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
  # The module is built for one interpreter version (its file name says which).
  math(EXPR glint_python_next "${Python3_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS
      "python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}), python3 (<< ${Python3_VERSION_MAJOR}.${glint_python_next}), python3-numpy")
  set(CPACK_COMPONENT_PYTHON_DESCRIPTION "glint as a Python module: import glint")
endif()
set(CPACK_COMPONENT_GLINT_DESCRIPTION "the glint command line, its scenarios, the cohort workflow and the 3D Slicer module")
include(CPack)
