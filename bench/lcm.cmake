# pool-bench-shot-server: pool-shot-server under load (bench/lcm/bench_shot_server.sh starts both,
# docs/lcm.md "Load benchmark"). Needs the LCM services' code (pool_lcm_tools, tools/lcm.cmake).
if(TARGET pool_lcm_tools)
  add_executable(pool-bench-shot-server ${CMAKE_CURRENT_SOURCE_DIR}/lcm/bench_shot_server.c)
  target_link_libraries(pool-bench-shot-server PRIVATE pool_lcm_tools pool_bench_util)
endif()
