# pool-game (tools/pool_game.c, tools/game/): a whole game under libpool games' rules, from a
# strategy command or strikes on standard input. Deferred to the end of tools/CMakeLists.txt
# because pool_tools is defined by sim.cmake, which is included after this file.
function(pool_game_setup)
  if(NOT TARGET pool_tools)
    return()
  endif()
  add_executable(pool-game ${CMAKE_CURRENT_SOURCE_DIR}/pool_game.c ${CMAKE_CURRENT_SOURCE_DIR}/game/peer.c)
  target_include_directories(pool-game PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(pool-game PRIVATE pool_tools pool_games m)
  install(TARGETS pool-game RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
cmake_language(DEFER CALL pool_game_setup)
