# Every dependency is a Debian 12 package; a missing one stops configure and names the package.
macro(rift_require pkg debian)
  find_package(${pkg} ${ARGN} QUIET)
  if(NOT ${pkg}_FOUND)
    message(FATAL_ERROR "Rift needs ${pkg}. On Debian 12: apt-get install ${debian}  "
                        "(or run scripts/test.sh, which installs everything).")
  endif()
endmacro()

rift_require(Eigen3 libeigen3-dev 3.3 NO_MODULE)
rift_require(TBB libtbb-dev)
rift_require(HDF5 libhdf5-dev COMPONENTS C)
rift_require(yaml-cpp libyaml-cpp-dev)
rift_require(nlohmann_json nlohmann-json3-dev)
rift_require(spdlog libspdlog-dev)
rift_require(fmt libfmt-dev)
rift_require(CLI11 libcli11-dev)
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
rift_require(CGAL libcgal-dev)

# METIS 5.1 ships no CMake package.
find_path(METIS_INCLUDE_DIR metis.h)
find_library(METIS_LIBRARY metis)
if(NOT METIS_INCLUDE_DIR OR NOT METIS_LIBRARY)
  message(FATAL_ERROR "Rift needs METIS. On Debian 12: apt-get install libmetis-dev")
endif()
add_library(rift::metis INTERFACE IMPORTED)
set_target_properties(rift::metis PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${METIS_INCLUDE_DIR}
                                             INTERFACE_LINK_LIBRARIES ${METIS_LIBRARY})

# hypre (BoomerAMG for the fluid pressure). Debian's libhypre-2.26 is built against OpenMPI, so a serial Rift
# still links MPI and calls MPI_Init (singleton mode: no mpirun needed; engine/linear/hypre_runtime.cpp).
rift_require(MPI libopenmpi-dev COMPONENTS CXX)
find_path(HYPRE_INCLUDE_DIR HYPRE.h PATH_SUFFIXES hypre)
find_library(HYPRE_LIBRARY HYPRE)
if(NOT HYPRE_INCLUDE_DIR OR NOT HYPRE_LIBRARY)
  message(FATAL_ERROR "Rift needs hypre. On Debian 12: apt-get install libhypre-dev")
endif()
add_library(rift::hypre INTERFACE IMPORTED)
set_target_properties(rift::hypre PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${HYPRE_INCLUDE_DIR}
                                             INTERFACE_LINK_LIBRARIES "${HYPRE_LIBRARY};MPI::MPI_CXX")

if(RIFT_BUILD_TESTS)
  rift_require(GTest libgtest-dev)
endif()
if(RIFT_BUILD_BENCH)
  rift_require(benchmark libbenchmark-dev)
endif()
