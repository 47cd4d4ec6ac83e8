# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# Locate the OpenMM this plugin builds against. OpenMM's PyPI wheel ships headers and libraries but no CMake
# config, so by default it is found through the Python interpreter (Python3_EXECUTABLE) without importing it:
# site-packages/openmm is the Python package, site-packages/OpenMM.libs the install tree. -DOPENMM_DIR=<prefix>
# (holding include/OpenMM.h and lib/libOpenMM.so) selects another install tree, e.g. a conda one.
#
# Sets OPENMM_DIR, OPENMM_VERSION (x.y.z), OPENMM_SWIG_VERSION (the SWIG that generated openmm's wrappers; empty
# when not found) and the imported target OpenMM::OpenMM.

set(_openmm_probe [=[
import importlib.metadata, importlib.util, os, re
spec = importlib.util.find_spec("openmm")
package = list(spec.submodule_search_locations)[0]
print(os.path.join(os.path.dirname(package), "OpenMM.libs"))
print(importlib.metadata.version("openmm"))
swig = ""
with open(os.path.join(package, "openmm.py")) as stream:
    for line in stream.readlines()[:5]:
        match = re.match(r"# Version (\S+)", line)
        if match:
            swig = match.group(1)
print(swig)
]=])
execute_process(COMMAND ${Python3_EXECUTABLE} -c "${_openmm_probe}"
                OUTPUT_VARIABLE _openmm_probe_output ERROR_VARIABLE _openmm_probe_error
                RESULT_VARIABLE _openmm_probe_failed OUTPUT_STRIP_TRAILING_WHITESPACE)
if(_openmm_probe_failed)
    message(FATAL_ERROR "${Python3_EXECUTABLE} has no OpenMM (pip install openmm): ${_openmm_probe_error}")
endif()
string(REPLACE "\n" ";" _openmm_probe_output "${_openmm_probe_output}")
list(GET _openmm_probe_output 0 _openmm_wheel_dir)
list(GET _openmm_probe_output 1 OPENMM_VERSION)
list(LENGTH _openmm_probe_output _openmm_probe_length)
set(OPENMM_SWIG_VERSION "")
if(_openmm_probe_length GREATER 2)
    list(GET _openmm_probe_output 2 OPENMM_SWIG_VERSION)
endif()

set(OPENMM_DIR "${_openmm_wheel_dir}" CACHE PATH "OpenMM install tree (include/, lib/)")
find_path(OPENMM_INCLUDE_DIR OpenMM.h PATHS ${OPENMM_DIR}/include NO_DEFAULT_PATH)
find_library(OPENMM_LIBRARY OpenMM PATHS ${OPENMM_DIR}/lib NO_DEFAULT_PATH)
if(NOT OPENMM_INCLUDE_DIR OR NOT OPENMM_LIBRARY)
    message(FATAL_ERROR "No OpenMM headers and library under OPENMM_DIR=${OPENMM_DIR} (need include/OpenMM.h and "
                        "lib/libOpenMM.so)")
endif()
set(OPENMM_PLUGIN_DIR "${OPENMM_DIR}/lib/plugins")
message(STATUS "OpenMM ${OPENMM_VERSION}: ${OPENMM_DIR} (Python wrappers made by SWIG ${OPENMM_SWIG_VERSION})")

add_library(OpenMM::OpenMM SHARED IMPORTED)
set_target_properties(OpenMM::OpenMM PROPERTIES
    IMPORTED_LOCATION ${OPENMM_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${OPENMM_INCLUDE_DIR})
