# pool-bench-fit: seconds for pool-fit on one shot and on 20 shots together (docs/measurements.md
# "pool-fit"). Needs tools/'s pool_fit_core (built when GSL is found).
if(TARGET pool_fit_core)
  add_executable(pool-bench-fit ${CMAKE_CURRENT_SOURCE_DIR}/bench_fit.c)
  target_link_libraries(pool-bench-fit PRIVATE pool_fit_core pool_bench_util)
endif()
