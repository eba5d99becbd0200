# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
#[==[.rst:
FindCHOLMOD
-----------

Finds CHOLMOD, the sparse Cholesky factorization of SuiteSparse, for distributions that ship no
CMake package for it (e.g. Debian 12 libsuitesparse-dev).

Imported target
^^^^^^^^^^^^^^^

``CHOLMOD::CHOLMOD``
  The cholmod library, its headers and suitesparseconfig.

Result variables
^^^^^^^^^^^^^^^^

``CHOLMOD_FOUND``, ``CHOLMOD_INCLUDE_DIR``, ``CHOLMOD_LIBRARY``, ``CHOLMOD_SUITESPARSECONFIG_LIBRARY``,
``CHOLMOD_VERSION``.
#]==]

find_path(CHOLMOD_INCLUDE_DIR
  NAMES cholmod.h
  PATH_SUFFIXES suitesparse
  DOC "Directory holding cholmod.h")
mark_as_advanced(CHOLMOD_INCLUDE_DIR)

find_library(CHOLMOD_LIBRARY
  NAMES cholmod
  DOC "CHOLMOD library")
mark_as_advanced(CHOLMOD_LIBRARY)

find_library(CHOLMOD_SUITESPARSECONFIG_LIBRARY
  NAMES suitesparseconfig
  DOC "SuiteSparse_config library")
mark_as_advanced(CHOLMOD_SUITESPARSECONFIG_LIBRARY)

# SuiteSparse 5 defines the version in cholmod_core.h, SuiteSparse 7 in cholmod.h.
set(_cholmod_version_header "${CHOLMOD_INCLUDE_DIR}/cholmod_core.h")
if (NOT EXISTS "${_cholmod_version_header}")
  set(_cholmod_version_header "${CHOLMOD_INCLUDE_DIR}/cholmod.h")
endif ()
if (CHOLMOD_INCLUDE_DIR AND EXISTS "${_cholmod_version_header}")
  file(STRINGS "${_cholmod_version_header}" _cholmod_version_lines
    REGEX "^#define CHOLMOD_(MAIN|SUB)_VERSION[ \t]+[0-9]+")
  string(REGEX REPLACE ".*CHOLMOD_MAIN_VERSION[ \t]+([0-9]+).*" "\\1"
    _cholmod_version_major "${_cholmod_version_lines}")
  string(REGEX REPLACE ".*CHOLMOD_SUB_VERSION[ \t]+([0-9]+).*" "\\1"
    _cholmod_version_minor "${_cholmod_version_lines}")
  if (_cholmod_version_major MATCHES "^[0-9]+$" AND _cholmod_version_minor MATCHES "^[0-9]+$")
    set(CHOLMOD_VERSION "${_cholmod_version_major}.${_cholmod_version_minor}")
  endif ()
  unset(_cholmod_version_lines)
  unset(_cholmod_version_major)
  unset(_cholmod_version_minor)
endif ()
unset(_cholmod_version_header)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS
    CHOLMOD_LIBRARY
    CHOLMOD_SUITESPARSECONFIG_LIBRARY
    CHOLMOD_INCLUDE_DIR
  VERSION_VAR CHOLMOD_VERSION)

if (CHOLMOD_FOUND)
  set(CHOLMOD_INCLUDE_DIRS "${CHOLMOD_INCLUDE_DIR}")
  set(CHOLMOD_LIBRARIES "${CHOLMOD_LIBRARY}" "${CHOLMOD_SUITESPARSECONFIG_LIBRARY}")
  if (NOT TARGET CHOLMOD::SuiteSparseConfig)
    add_library(CHOLMOD::SuiteSparseConfig UNKNOWN IMPORTED)
    set_target_properties(CHOLMOD::SuiteSparseConfig
      PROPERTIES
        IMPORTED_LOCATION "${CHOLMOD_SUITESPARSECONFIG_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}")
  endif ()
  if (NOT TARGET CHOLMOD::CHOLMOD)
    add_library(CHOLMOD::CHOLMOD UNKNOWN IMPORTED)
    set_target_properties(CHOLMOD::CHOLMOD
      PROPERTIES
        IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
        INTERFACE_LINK_LIBRARIES "CHOLMOD::SuiteSparseConfig")
  endif ()
endif ()
