# Scenario/result JSON layer (pool_scenario), pool-sim, pool-rack and pool-plot.
find_package(PkgConfig REQUIRED)
pkg_check_modules(JANSSON REQUIRED IMPORTED_TARGET jansson)

file(GLOB POOL_SCENARIO_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/common/*.c)
add_library(pool_scenario STATIC ${POOL_SCENARIO_SOURCES})
target_include_directories(pool_scenario PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/common)
target_link_libraries(pool_scenario PUBLIC pool PkgConfig::JANSSON m)

# While the engine (pool_sim_*) is still being written, programs using it cannot link; build
# them only once libpool defines pool_sim_step, so the rest of the tree keeps building.
file(GLOB POOL_ENGINE_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/libpool/src/*.c)
set(POOL_HAVE_ENGINE OFF)
foreach(source ${POOL_ENGINE_SOURCES})
  file(STRINGS ${source} hit REGEX "^int pool_sim_step\\(")
  if(hit)
    set(POOL_HAVE_ENGINE ON)
  endif()
endforeach()
set(POOL_HAVE_ENGINE ${POOL_HAVE_ENGINE} CACHE INTERNAL "libpool defines the simulation engine")

if(POOL_HAVE_ENGINE)
  add_executable(pool-sim ${CMAKE_CURRENT_SOURCE_DIR}/pool_sim.c)
  target_link_libraries(pool-sim PRIVATE pool_scenario)

  add_executable(pool-rack ${CMAKE_CURRENT_SOURCE_DIR}/pool_rack.c)
  target_link_libraries(pool-rack PRIVATE pool_scenario)

  install(TARGETS pool-sim pool-rack RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
else()
  message(STATUS "pool-sim, pool-rack: waiting for the libpool engine (pool_sim_step)")
endif()
if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/pool-plot)
  install(PROGRAMS ${CMAKE_CURRENT_SOURCE_DIR}/pool-plot DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
