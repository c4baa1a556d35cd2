# LCM services: message conversion, pool-shot-server, pool-lcm-subscribe (its load benchmark is
# bench/lcm.cmake's) and pool-sim's --lcm-url / --playback (tools/lcm/sim_publish.c, compiled into pool-sim only when
# LCM is built, so pool-sim builds without it). The message types come from lcm_types/
# (target pool_lcm_c). Deferred to the end of tools/CMakeLists.txt because pool_tools and
# pool-sim are defined by other tools/*.cmake parts.
function(pool_lcm_tools_setup)
  if(NOT POOL_BUILD_LCM OR NOT EXISTS ${CMAKE_SOURCE_DIR}/lcm_types/CMakeLists.txt)
    return()
  endif()
  # The same checks as lcm_types/CMakeLists.txt, which defines pool_lcm_c when they pass.
  find_program(POOL_LCM_GEN lcm-gen PATHS /usr/bin NO_DEFAULT_PATH)
  find_program(POOL_LCM_GEN lcm-gen)
  find_library(POOL_LCM_LIBRARY lcm)
  find_path(POOL_LCM_INCLUDE_DIR lcm/lcm.h)
  if(NOT POOL_LCM_GEN OR NOT POOL_LCM_LIBRARY OR NOT POOL_LCM_INCLUDE_DIR OR NOT TARGET pool_tools)
    message(STATUS "LCM services not built (needs lcm-gen, liblcm and pool_tools)")
    return()
  endif()
  set(dir ${CMAKE_CURRENT_SOURCE_DIR}/lcm)

  add_library(pool_lcm_tools STATIC ${dir}/lcm_convert.c ${dir}/lcm_service.c ${dir}/sim_publish.c)
  target_include_directories(pool_lcm_tools PUBLIC ${dir})
  target_link_libraries(pool_lcm_tools PUBLIC pool_lcm_c pool_tools pool_games pool m)

  add_executable(pool-shot-server ${dir}/shot_server.c)
  target_link_libraries(pool-shot-server PRIVATE pool_lcm_tools)

  add_executable(pool-lcm-subscribe ${dir}/subscribe.c)
  target_link_libraries(pool-lcm-subscribe PRIVATE pool_lcm_tools)

  install(TARGETS pool-shot-server pool-lcm-subscribe RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(PROGRAMS ${CMAKE_CURRENT_SOURCE_DIR}/pool_lcm_subscribe.py DESTINATION ${CMAKE_INSTALL_BINDIR})

  if(TARGET pool-sim)
    target_link_libraries(pool-sim PRIVATE pool_lcm_tools)
    target_compile_definitions(pool-sim PRIVATE POOL_HAVE_LCM=1)
  endif()
endfunction()
cmake_language(DEFER CALL pool_lcm_tools_setup)
