# pool-bench-models: the cost of issue 12's optional models (one cushion impact by each law; the
# break with each cushion model) and the accuracy of the Mathavan integration against its
# fixed-step reference (tools/mathavan_reference.c). Calls libpool's internal laws, so it links
# the internal archive.
add_executable(pool-bench-models ${CMAKE_CURRENT_SOURCE_DIR}/bench_models.c ${CMAKE_SOURCE_DIR}/tools/mathavan_reference.c)
target_link_libraries(pool-bench-models PRIVATE pool_bench_util pool_internal m)
target_include_directories(pool-bench-models PRIVATE ${CMAKE_SOURCE_DIR}/libpool/src ${CMAKE_SOURCE_DIR}/tools)
