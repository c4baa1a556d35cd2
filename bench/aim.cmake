# pool-bench-aim: seconds for pool-aim's best shot of positions left by breaks, on every core
# (docs/measurements.md "pool-aim"). Needs libpool planning.
if(TARGET pool_planning)
  add_executable(pool-bench-aim ${CMAKE_CURRENT_SOURCE_DIR}/bench_aim.c)
  target_link_libraries(pool-bench-aim PRIVATE pool_planning pool_bench_util m)
endif()
