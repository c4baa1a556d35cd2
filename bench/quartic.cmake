# pool-bench-quartic: libpool's quartic solver against GSL's gsl_poly_complex_solve.
# Built only when GSL is found (pkg-config gsl); the executable lands in the build's bench/ dir.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(POOL_GSL QUIET IMPORTED_TARGET gsl)
endif()
if(POOL_GSL_FOUND)
  add_executable(pool-bench-quartic
    ${CMAKE_CURRENT_SOURCE_DIR}/bench_quartic.c
    ${CMAKE_CURRENT_SOURCE_DIR}/bench_quartic_gen.c
    ${CMAKE_CURRENT_SOURCE_DIR}/bench_quartic_ref.c)
  target_link_libraries(pool-bench-quartic PRIVATE pool_bench_util pool PkgConfig::POOL_GSL m)
  # clock_gettime, sysconf
  target_compile_definitions(pool-bench-quartic PRIVATE _POSIX_C_SOURCE=200809L)
  set_target_properties(pool-bench-quartic PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
else()
  message(STATUS "GSL not found: pool-bench-quartic is not built")
endif()
