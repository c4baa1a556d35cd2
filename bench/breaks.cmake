# pool-bench-breaks: jittered breaks under each model set and their statistics (bench/bench_breaks.c,
# docs/measurements.md "Breaks"); tools/pool-break-plot draws its --json, bench/breaks/ runs the
# same breaks in pooltool. On the commands' code (pool_tools: the model sets' names, the JSON writer).
add_executable(pool-bench-breaks ${CMAKE_CURRENT_SOURCE_DIR}/bench_breaks.c)
target_link_libraries(pool-bench-breaks PRIVATE pool_tools pool_bench_util m)
install(TARGETS pool-bench-breaks RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
