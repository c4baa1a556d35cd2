# pool-bench-shot: whole-shot timing benchmark of libpool (median / min, events/s, peak memory).
add_executable(pool-bench-shot ${CMAKE_CURRENT_SOURCE_DIR}/bench_shot.c)
target_link_libraries(pool-bench-shot PRIVATE pool_bench_util pool m)
install(TARGETS pool-bench-shot RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# pool-bench-trajectory: the C reference of Sim.trajectory (bench/bench_trajectory.py).
add_executable(pool-bench-trajectory ${CMAKE_CURRENT_SOURCE_DIR}/bench_trajectory.c)
target_link_libraries(pool-bench-trajectory PRIVATE pool_bench_util pool m)
