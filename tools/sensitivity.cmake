# pool-sensitivity (tools/pool_sensitivity.c, tools/sensitivity/): noise on a strike, N samples
# of libpool games' noise (pool/noise.h), the clouds of final positions and their statistics
# (GSL). Only this tool links GSL; libpool itself does not. Deferred to the end of tools/CMakeLists.txt because
# pool_tools is defined by sim.cmake, which is included after this file.
function(pool_sensitivity_setup)
  if(NOT TARGET pool_tools)
    return()
  endif()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(GSL IMPORTED_TARGET gsl)
  if(NOT GSL_FOUND)
    message(STATUS "pool-sensitivity not built (needs GSL: libgsl-dev, installed by tools/setup.sh)")
    return()
  endif()
  find_package(Threads REQUIRED)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/sensitivity/*.c)
  add_executable(pool-sensitivity ${CMAKE_CURRENT_SOURCE_DIR}/pool_sensitivity.c ${sources})
  target_include_directories(pool-sensitivity PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(pool-sensitivity PRIVATE pool_tools PkgConfig::GSL Threads::Threads m)
  install(TARGETS pool-sensitivity RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
cmake_language(DEFER CALL pool_sensitivity_setup)
