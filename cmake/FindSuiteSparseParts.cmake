# SuiteSparse 5.12 on Debian ships no CMake config: find CHOLMOD, UMFPACK and KLU by hand (targets in
# our own namespace, so that packages with their own SuiteSparse finder do not collide).
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
find_library(UMFPACK_LIBRARY umfpack REQUIRED)
add_library(superdex::CHOLMOD INTERFACE IMPORTED)
set_target_properties(superdex::CHOLMOD PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "${CHOLMOD_LIBRARY};${SUITESPARSECONFIG_LIBRARY}")

add_library(superdex::UMFPACK INTERFACE IMPORTED)
set_target_properties(superdex::UMFPACK PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "${UMFPACK_LIBRARY};${CHOLMOD_LIBRARY};${SUITESPARSECONFIG_LIBRARY}")


# KLU (with its orderings BTF, AMD, COLAMD): the LU of sparse systems with little fill.
find_library(KLU_LIBRARY klu REQUIRED)
find_library(BTF_LIBRARY btf REQUIRED)
find_library(AMD_LIBRARY amd REQUIRED)
find_library(COLAMD_LIBRARY colamd REQUIRED)
add_library(superdex::KLU INTERFACE IMPORTED)
set_target_properties(superdex::KLU PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES
    "${KLU_LIBRARY};${BTF_LIBRARY};${AMD_LIBRARY};${COLAMD_LIBRARY};${SUITESPARSECONFIG_LIBRARY}")
