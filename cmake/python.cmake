# Finds what the Python module needs and sets TS_PYTHON (ON when it is built). TREESKETCH_PYTHON:
# ON (missing packages are an error), OFF, AUTO (built when Python 3 with NumPy and pybind11 are
# found). Never in a sanitizer build: the module would be loaded into an interpreter that is not
# instrumented (the sanitizer build tests the library through the C++ tests instead).
set(TS_PYTHON OFF)
if(TREESKETCH_PYTHON STREQUAL "OFF")
  return()
endif()
if(TREESKETCH_SANITIZE)
  if(TREESKETCH_PYTHON STREQUAL "ON")
    message(WARNING "TREESKETCH_PYTHON=ON ignored: the Python module is not built with TREESKETCH_SANITIZE")
  endif()
  return()
endif()
# The system interpreter, the one Debian's python3-numpy and python3-pybind11 are installed for
# (a pyenv or venv python3 may come first on PATH). -DPython3_EXECUTABLE=... picks another.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter the module is built for")
endif()
if(TREESKETCH_PYTHON STREQUAL "ON")
  find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module NumPy)
  find_package(pybind11 2.6 CONFIG REQUIRED)
else()
  find_package(Python3 QUIET COMPONENTS Interpreter Development.Module NumPy)
  if(Python3_FOUND)
    find_package(pybind11 2.6 CONFIG QUIET)
  endif()
  if(NOT Python3_FOUND OR NOT pybind11_FOUND)
    message(STATUS "Python module: not built (needs python3-dev, python3-numpy, python3-pybind11)")
    return()
  endif()
endif()
set(TS_PYTHON ON)
message(STATUS "Python module: built for ${Python3_EXECUTABLE} (${Python3_VERSION}), pybind11 ${pybind11_VERSION}")
