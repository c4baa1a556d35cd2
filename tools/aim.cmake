# pool-aim (tools/pool_aim.c, tools/aim/): the best shots of a position ranked under noise, with
# libpool planning (planning/). pool_aim_tool is shared with the LCM shot planner (lcm.cmake).
# Deferred to the end of tools/CMakeLists.txt because pool_tools is defined by sim.cmake.
function(pool_aim_setup)
  if(NOT TARGET pool_tools OR NOT TARGET pool_planning)
    return()
  endif()
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/aim/*.c)
  add_library(pool_aim_tool STATIC ${sources})
  target_include_directories(pool_aim_tool PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(pool_aim_tool PUBLIC pool_tools pool_planning m)
  add_executable(pool-aim ${CMAKE_CURRENT_SOURCE_DIR}/pool_aim.c)
  target_link_libraries(pool-aim PRIVATE pool_aim_tool)
  install(TARGETS pool-aim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  # pool-aim-trials: the evidence campaign (random layouts with a straight-in shot; the tests and
  # docs/measurements.md).
  add_executable(pool-aim-trials ${CMAKE_CURRENT_SOURCE_DIR}/aim_trials.c)
  target_link_libraries(pool-aim-trials PRIVATE pool_tools pool_planning m)
endfunction()
cmake_language(DEFER CALL pool_aim_setup)

