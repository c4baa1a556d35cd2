# pool-bench-games: the rules' cost per shot against the shot's simulation (docs/measurements.md
# "Games"). Public API only (libpool and libpool_games).
add_executable(pool-bench-games ${CMAKE_CURRENT_SOURCE_DIR}/bench_games.c)
target_link_libraries(pool-bench-games PRIVATE pool_games pool_bench_util m)
