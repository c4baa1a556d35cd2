# pool-bench-scale: libpool's cost per event against the ball count, with the schedule's
# all-pairs search and the broadphase grid (bench/bench_scale.c, docs/measurements.md). It sets
# the search through an internal function, so libpool comes from the internal archive (listed
# before libpool.a, it defines every libpool symbol pool_tools asks for: one copy of libpool).
add_executable(pool-bench-scale ${CMAKE_CURRENT_SOURCE_DIR}/bench_scale.c)
target_include_directories(pool-bench-scale PRIVATE ${CMAKE_SOURCE_DIR}/libpool/src)
target_link_libraries(pool-bench-scale PRIVATE pool_bench_util pool_tools pool_internal m)
