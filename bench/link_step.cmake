# pool-bench-link-step: time per LINK step (libpool/src/link_step.c) on clusters of 2, 3 and 16
# balls, median / min. pool_link_step is internal, so it links the internal archive and sees
# libpool/src; the executable lands in the build's bench/ dir.
add_executable(pool-bench-link-step ${CMAKE_CURRENT_SOURCE_DIR}/bench_link_step.c)
target_link_libraries(pool-bench-link-step PRIVATE pool_bench_util pool_internal m)
target_include_directories(pool-bench-link-step PRIVATE ${CMAKE_SOURCE_DIR}/libpool/src)
set_target_properties(pool-bench-link-step PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
