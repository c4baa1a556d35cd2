# pool-bench-lemke: libpool's lexicographic Lemke (an internal function, so it links the internal
# archive) on random LINK friction LCPs; the generator is the unit test's
# (tests/unit/lemke_friction_lcp.h). Built, not a test; the executable lands in the build's bench/.
add_executable(pool-bench-lemke ${CMAKE_CURRENT_SOURCE_DIR}/bench_lemke.c)
target_include_directories(pool-bench-lemke PRIVATE ${CMAKE_SOURCE_DIR}/libpool/src ${CMAKE_SOURCE_DIR}/tests/unit)
target_link_libraries(pool-bench-lemke PRIVATE pool_bench_util pool_internal m)
target_compile_definitions(pool-bench-lemke PRIVATE _POSIX_C_SOURCE=200809L)
set_target_properties(pool-bench-lemke PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
