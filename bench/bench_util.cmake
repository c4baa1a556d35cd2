# pool_bench_util: clock, median/minimum and machine description shared by the benchmark tools
# (pool-bench-shot, pool-bench-shot-server; pool-bench-quartic can link it too). libc only.
add_library(pool_bench_util STATIC ${CMAKE_CURRENT_SOURCE_DIR}/common/bench_util.c)
target_include_directories(pool_bench_util PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/common)
