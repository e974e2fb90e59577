# SPDX-License-Identifier: MIT
# JACOBID_PYTHON: the Python module `jacobid` (python/, docs/python.md), built with Debian's pybind11
# (python3-pybind11) for the system interpreter. Default ON when Python 3 (interpreter + headers) and
# pybind11 are found, OFF otherwise (said in a message); the sanitizer and cross builds turn it off.
#
# The interpreter: /usr/bin/python3 unless Python3_EXECUTABLE is given. Debian's pybind11 and numpy are
# installed for it; a pyenv or venv python3 first on PATH would build a module those packages do not
# serve (and CI's fresh Debian has only /usr/bin/python3).
set(JACOBID_PYTHON_REASON "")
if(CMAKE_CROSSCOMPILING)
  set(JACOBID_PYTHON_REASON "cross build (the module is for the build machine's interpreter)")
else()
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter of the jacobid module and its tests")
  endif()
  find_package(Python3 3.9 QUIET COMPONENTS Interpreter Development.Module)
  if(NOT Python3_FOUND)
    set(JACOBID_PYTHON_REASON "Python 3 with its headers not found (Debian: python3-dev)")
  else()
    find_package(pybind11 2.6 CONFIG QUIET)
    if(NOT pybind11_FOUND)
      set(JACOBID_PYTHON_REASON "pybind11 not found (Debian: python3-pybind11)")
    endif()
  endif()
endif()
if(JACOBID_PYTHON_REASON STREQUAL "")
  option(JACOBID_PYTHON "Build the Python module jacobid (python/, needs python3-dev and python3-pybind11)" ON)
else()
  option(JACOBID_PYTHON "Build the Python module jacobid (python/, needs python3-dev and python3-pybind11)" OFF)
  if(NOT JACOBID_PYTHON)
    message(STATUS "jacobid: the Python module is not built: ${JACOBID_PYTHON_REASON}")
  endif()
endif()
if(NOT JACOBID_PYTHON AND JACOBID_PYTHON_REASON STREQUAL "")
  message(STATUS "jacobid: the Python module is not built: JACOBID_PYTHON=OFF")
endif()
if(JACOBID_PYTHON AND NOT JACOBID_PYTHON_REASON STREQUAL "")
  message(FATAL_ERROR "JACOBID_PYTHON=ON but ${JACOBID_PYTHON_REASON}")
endif()

# A ctest test that says why the module's tests do not run (exit 77: reported as skipped, not passed).
function(jacobid_python_skip_test)
  set(why "${JACOBID_PYTHON_REASON}")
  if(why STREQUAL "")
    set(why "JACOBID_PYTHON=OFF")
  endif()
  if(NOT JACOBID_BUILD_HOST_TOOLS)
    set(why "JACOBID_BUILD_HOST_TOOLS=OFF")
  endif()
  add_test(NAME python.module COMMAND sh -c "echo 'python.module skipped: ${why}'; exit 77")
  set_tests_properties(python.module PROPERTIES SKIP_RETURN_CODE 77 LABELS "integration;python")
endfunction()
