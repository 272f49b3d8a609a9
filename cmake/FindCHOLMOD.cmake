# Finds SuiteSparse CHOLMOD (Debian's libsuitesparse-dev ships no CMake config
# in 5.x) and defines the imported target SuiteSparse::CHOLMOD, which also
# carries METIS (CHOLMOD's nested-dissection ordering) and the BLAS/LAPACK.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig)
find_library(AMD_LIBRARY amd)
find_library(CAMD_LIBRARY camd)
find_library(COLAMD_LIBRARY colamd)
find_library(CCOLAMD_LIBRARY ccolamd)
find_library(METIS_LIBRARY metis)
find_package(BLAS REQUIRED)
find_package(LAPACK REQUIRED)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR
  SUITESPARSE_CONFIG_LIBRARY AMD_LIBRARY COLAMD_LIBRARY METIS_LIBRARY)
if(CHOLMOD_FOUND AND NOT TARGET SuiteSparse::CHOLMOD)
  add_library(SuiteSparse::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${AMD_LIBRARY};${CAMD_LIBRARY};${COLAMD_LIBRARY};${CCOLAMD_LIBRARY};${METIS_LIBRARY};${SUITESPARSE_CONFIG_LIBRARY};${LAPACK_LIBRARIES};${BLAS_LIBRARIES}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY SUITESPARSE_CONFIG_LIBRARY AMD_LIBRARY
  CAMD_LIBRARY COLAMD_LIBRARY CCOLAMD_LIBRARY METIS_LIBRARY)
