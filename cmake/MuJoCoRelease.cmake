# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# mujoco::mujoco from the official MuJoCo release: the mujoco-core wheel that scripts/setup.sh
# installs into the project-local environment (.venv) at the version pinned in requirements.txt.
#
#   MJF_MUJOCO_VERSION   the pinned version ("4.0.1"), read from requirements.txt
#   MJF_MUJOCO_ROOT      the folder holding include/mujoco/ and libmujoco.so.<version>; by default
#                        asked of MJF_PYTHON_ENV's interpreter (where its `mujoco` package lives)
#   MJF_MUJOCO_LIBRARY   the library file every target of this build links and runs with
#
# Only this exact version is accepted: headers and library of another release are refused at
# configure time, naming both versions, so a build never mixes two engines.

file(STRINGS ${CMAKE_SOURCE_DIR}/requirements.txt mjf_core_pin REGEX "^mujoco-core==")
string(REGEX REPLACE "^mujoco-core==([0-9.]+).*" "\\1" MJF_MUJOCO_VERSION "${mjf_core_pin}")
if(NOT MJF_MUJOCO_VERSION MATCHES "^[0-9]+\\.[0-9]+\\.[0-9]+$")
  message(FATAL_ERROR "requirements.txt: no exact 'mujoco-core==X.Y.Z' pin found")
endif()

set(MJF_PYTHON_ENV ${CMAKE_SOURCE_DIR}/.venv CACHE PATH
    "the project-local Python environment that holds the pinned MuJoCo (scripts/setup.sh)")
set(mjf_env_python ${MJF_PYTHON_ENV}/bin/python)
if(SKBUILD AND Python_EXECUTABLE)
  # Under pip: the interpreter pip builds for, whose environment holds the pinned mujoco.
  set(mjf_env_python ${Python_EXECUTABLE})
endif()
if(NOT MJF_MUJOCO_ROOT)
  if(NOT EXISTS ${mjf_env_python})
    message(FATAL_ERROR "MuJoCo ${MJF_MUJOCO_VERSION}: no environment at ${MJF_PYTHON_ENV} "
                        "(run scripts/setup.sh, or pass -DMJF_MUJOCO_ROOT=<folder of the release>)")
  endif()
  # find_spec locates the package without importing it (no engine is loaded at configure time).
  execute_process(
    COMMAND ${mjf_env_python} -c
            "import importlib.util, os; print(os.path.dirname(importlib.util.find_spec('mujoco').origin))"
    OUTPUT_VARIABLE mjf_package_dir OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE mjf_rc
    ERROR_VARIABLE mjf_err)
  if(NOT mjf_rc EQUAL 0)
    message(FATAL_ERROR "MuJoCo ${MJF_MUJOCO_VERSION}: the mujoco package is not in "
                        "${MJF_PYTHON_ENV} (run scripts/setup.sh): ${mjf_err}")
  endif()
  set(MJF_MUJOCO_ROOT ${mjf_package_dir} CACHE PATH "folder of the MuJoCo release" FORCE)
endif()

set(MJF_MUJOCO_LIBRARY ${MJF_MUJOCO_ROOT}/libmujoco.so.${MJF_MUJOCO_VERSION})
set(mjf_header ${MJF_MUJOCO_ROOT}/include/mujoco/mujoco.h)
if(NOT EXISTS ${MJF_MUJOCO_LIBRARY} OR NOT EXISTS ${mjf_header})
  message(FATAL_ERROR "MuJoCo ${MJF_MUJOCO_VERSION}: ${MJF_MUJOCO_ROOT} lacks "
                      "libmujoco.so.${MJF_MUJOCO_VERSION} or include/mujoco/mujoco.h")
endif()
# mjVERSION_HEADER is major * 1000000 + minor * 1000 + patch (4.0.1 -> 4000001).
file(STRINGS ${mjf_header} mjf_header_line REGEX "^#define mjVERSION_HEADER ")
string(REGEX MATCH "[0-9]+" mjf_header_number "${mjf_header_line}")
string(REPLACE "." ";" mjf_parts ${MJF_MUJOCO_VERSION})
list(GET mjf_parts 0 mjf_major)
list(GET mjf_parts 1 mjf_minor)
list(GET mjf_parts 2 mjf_patch)
math(EXPR mjf_expected "${mjf_major} * 1000000 + ${mjf_minor} * 1000 + ${mjf_patch}")
if(NOT mjf_header_number EQUAL mjf_expected)
  message(FATAL_ERROR "MuJoCo headers in ${MJF_MUJOCO_ROOT} are version ${mjf_header_number}, "
                      "requirements.txt pins ${MJF_MUJOCO_VERSION} (${mjf_expected})")
endif()

add_library(mujoco::mujoco SHARED IMPORTED GLOBAL)
set_target_properties(mujoco::mujoco PROPERTIES
  IMPORTED_LOCATION ${MJF_MUJOCO_LIBRARY}
  IMPORTED_SONAME libmujoco.so.${MJF_MUJOCO_VERSION}
  INTERFACE_INCLUDE_DIRECTORIES ${MJF_MUJOCO_ROOT}/include)
message(STATUS "MuJoCo ${MJF_MUJOCO_VERSION}: ${MJF_MUJOCO_LIBRARY}")
