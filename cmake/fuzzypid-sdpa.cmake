# SDPA (Debian libsdpa-dev, a static library without a CMake or pkg-config file), the
# semidefinite-program solver of the sim part's Lyapunov certificate, wrapped in the imported
# target `fuzzypid_sdpa` with what /usr/share/sdpa/make.inc says it links: MUMPS (sequential),
# SCOTCH, LAPACK and BLAS, gfortran. Used by the build (src/sim/CMakeLists.txt) and by the
# installed package config, whose exported sim library names this target as a link-only
# dependency. SDPA is GPL-2+: a program that links fuzzypid::sim links it (docs/margins.md).
if(NOT TARGET fuzzypid_sdpa)
  find_path(FUZZYPID_SDPA_INCLUDE_DIR sdpa_call.h REQUIRED)
  find_library(FUZZYPID_SDPA_LIBRARY NAMES sdpa REQUIRED)
  find_library(FUZZYPID_DMUMPS_LIBRARY NAMES dmumps_seq REQUIRED)
  find_library(FUZZYPID_MUMPS_COMMON_LIBRARY NAMES mumps_common_seq REQUIRED)
  find_library(FUZZYPID_MPISEQ_LIBRARY NAMES mpiseq_seq mpiseq REQUIRED)
  find_library(FUZZYPID_PORD_LIBRARY NAMES pord_seq pord REQUIRED)
  find_package(LAPACK REQUIRED)
  add_library(fuzzypid_sdpa INTERFACE IMPORTED)
  target_include_directories(fuzzypid_sdpa SYSTEM INTERFACE ${FUZZYPID_SDPA_INCLUDE_DIR})
  target_link_libraries(fuzzypid_sdpa INTERFACE
    ${FUZZYPID_SDPA_LIBRARY} ${FUZZYPID_DMUMPS_LIBRARY} ${FUZZYPID_MUMPS_COMMON_LIBRARY}
    ${FUZZYPID_MPISEQ_LIBRARY} ${FUZZYPID_PORD_LIBRARY} scotch esmumps ${LAPACK_LIBRARIES}
    gfortran pthread)
endif()
