# Finds UMFPACK from Debian's libsuitesparse-dev (no CMake config of its own in Debian 12) and
# defines the imported target UMFPACK::UMFPACK. Used by the adjoint's direct sparse LU fallback
# (engine/weft/diff/DirectLuSolver), through Eigen's UmfPackSupport module.
find_path(UMFPACK_INCLUDE_DIR umfpack.h PATH_SUFFIXES suitesparse)
find_library(UMFPACK_LIBRARY umfpack)
find_library(UMFPACK_AMD_LIBRARY amd)
find_library(UMFPACK_CONFIG_LIBRARY suitesparseconfig)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(UMFPACK REQUIRED_VARS UMFPACK_LIBRARY UMFPACK_INCLUDE_DIR
                                  UMFPACK_AMD_LIBRARY UMFPACK_CONFIG_LIBRARY)
if(UMFPACK_FOUND AND NOT TARGET UMFPACK::UMFPACK)
  add_library(UMFPACK::UMFPACK UNKNOWN IMPORTED)
  set_target_properties(UMFPACK::UMFPACK PROPERTIES
    IMPORTED_LOCATION "${UMFPACK_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${UMFPACK_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${UMFPACK_AMD_LIBRARY};${UMFPACK_CONFIG_LIBRARY}")
endif()
mark_as_advanced(UMFPACK_INCLUDE_DIR UMFPACK_LIBRARY UMFPACK_AMD_LIBRARY UMFPACK_CONFIG_LIBRARY)
