# The commands' shared code (pool_tools: command-line plumbing, atomic output files, the pool-view
# page, the scale scenes, the batch layout file) on the scenario library (scenario/), then
# pool-sim, pool-rack and pool-plot.
file(GLOB POOL_TOOLS_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/common/*.c)
# bench_util.c is pool_bench_util (bench_util.cmake): benchmarks link it without jansson.
list(REMOVE_ITEM POOL_TOOLS_SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/common/bench_util.c)
# The pool-view page template, built into pool_tools for pool-sim --view (view_page.c).
set(POOL_VIEW_TEMPLATE_C ${CMAKE_CURRENT_BINARY_DIR}/view_template.c)
add_custom_command(OUTPUT ${POOL_VIEW_TEMPLATE_C}
  COMMAND ${CMAKE_COMMAND} -DINPUT=${CMAKE_CURRENT_SOURCE_DIR}/view/pool_view.html
          -DOUTPUT=${POOL_VIEW_TEMPLATE_C} -P ${CMAKE_CURRENT_SOURCE_DIR}/view/embed.cmake
  DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/view/pool_view.html ${CMAKE_CURRENT_SOURCE_DIR}/view/embed.cmake
  COMMENT "Embedding the pool-view page" VERBATIM)
add_library(pool_tools STATIC ${POOL_TOOLS_SOURCES} ${POOL_VIEW_TEMPLATE_C})
target_include_directories(pool_tools PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/common)
target_link_libraries(pool_tools PUBLIC pool_scenario_internal pool pool_games m)

add_executable(pool-sim ${CMAKE_CURRENT_SOURCE_DIR}/pool_sim.c)
target_link_libraries(pool-sim PRIVATE pool_tools)

add_executable(pool-rack ${CMAKE_CURRENT_SOURCE_DIR}/pool_rack.c)
target_link_libraries(pool-rack PRIVATE pool_tools)

install(TARGETS pool-sim pool-rack RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(PROGRAMS ${CMAKE_CURRENT_SOURCE_DIR}/pool-plot ${CMAKE_CURRENT_SOURCE_DIR}/pool-fidelity-plot
                 ${CMAKE_CURRENT_SOURCE_DIR}/pool-view
        DESTINATION ${CMAKE_INSTALL_BINDIR})
# pool-view finds its page in ../share/libpool/ once installed.
install(FILES ${CMAKE_CURRENT_SOURCE_DIR}/view/pool_view.html DESTINATION ${CMAKE_INSTALL_DATADIR}/libpool)
