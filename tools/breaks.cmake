# pool-bench-breaks: jittered breaks under each model set and their statistics (tools/bench_breaks.c,
# docs/measurements.md "Breaks"); pool-break-plot draws its --json. Deferred like
# sensitivity.cmake: pool_tools (the commands' code on the scenario library) is defined by sim.cmake.
function(pool_breaks_setup)
  if(NOT TARGET pool_tools)
    return()
  endif()
  add_executable(pool-bench-breaks ${CMAKE_CURRENT_SOURCE_DIR}/bench_breaks.c)
  target_link_libraries(pool-bench-breaks PRIVATE pool_tools pool_bench_util m)
  install(TARGETS pool-bench-breaks RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
cmake_language(DEFER CALL pool_breaks_setup)
