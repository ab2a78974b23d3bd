# The Python module (python/): pybind11 and numpy from Debian (pybind11-dev, python3-dev,
# python3-numpy). GLINT_BUILD_PYTHON defaults to ON when they are found; set ON explicitly,
# a missing package stops configure naming it, set OFF, nothing Python is built.
#
# note: the Debian packages serve Debian's interpreter, /usr/bin/python3. Another python3
# earlier on PATH (pyenv, a venv) sees none of them, so Debian's is chosen when present;
# -DPython3_EXECUTABLE=… picks another (it then needs numpy and pytest of its own).
# note: a build with neither the module nor the tests (preset app, tools/demo) needs no Python and
# looks for none: probing would run the interpreter, which reads whatever Python packages the
# machine holds, and make configure touch packages the app set does not install (issue 51).
set(glint_python_default OFF)
if(NOT (DEFINED GLINT_BUILD_PYTHON AND NOT GLINT_BUILD_PYTHON AND DEFINED GLINT_BUILD_TESTS
        AND NOT GLINT_BUILD_TESTS))
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter of the glint module and its tests")
  endif()
  find_package(Python3 QUIET COMPONENTS Interpreter Development.Module)
  if(Python3_FOUND)
    find_package(pybind11 2.6 CONFIG QUIET)
  endif()
  # The module hands out numpy arrays: numpy must import in that interpreter.
  set(glint_numpy_found FALSE)
  if(Python3_FOUND)
    execute_process(COMMAND ${Python3_EXECUTABLE} -c "import numpy" RESULT_VARIABLE numpy_missing
                    OUTPUT_QUIET ERROR_QUIET)
    if(numpy_missing EQUAL 0)
      set(glint_numpy_found TRUE)
    endif()
  endif()
  if(Python3_FOUND AND pybind11_FOUND AND glint_numpy_found)
    set(glint_python_default ON)
  else()
    set(glint_python_default OFF)
  endif()
endif()
option(GLINT_BUILD_PYTHON "Build the glint Python module (python/)" ${glint_python_default})
if(GLINT_BUILD_PYTHON)
  glint_require(Python3_FOUND python3-dev)
  glint_require(pybind11_FOUND pybind11-dev)
  glint_require(glint_numpy_found python3-numpy)
  # The module links the static glint libraries into a shared object.
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  # Where `cmake --install` puts the module, relative to the prefix: Debian's convention for
  # packaged modules (what /usr/bin/python3 searches under /usr). For another prefix, put
  # PREFIX/<this> on PYTHONPATH, or set it to that interpreter's site folder.
  set(GLINT_PYTHON_INSTALL_DIR lib/python3/dist-packages CACHE STRING
      "Install folder of the Python module, relative to the install prefix")
  message(STATUS "glint: Python module for ${Python3_EXECUTABLE} (${Python3_VERSION}), pybind11 ${pybind11_VERSION}")
elseif(glint_python_default)
  message(STATUS "glint: Python module off (GLINT_BUILD_PYTHON=OFF)")
else()
  message(STATUS "glint: Python module off: pybind11, Python's headers or numpy not found "
                 "(install the Debian packages pybind11-dev python3-dev python3-numpy)")
endif()
