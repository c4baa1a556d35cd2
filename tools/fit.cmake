# pool-fit (tools/pool_fit.c, tools/fit/): strike and table parameters from observed tracks by
# nonlinear least squares (GSL's gsl_multifit_nlinear). Only the tools link GSL; libpool does not.
# pool_fit_core is the fit without the command line, for the tests' synthetic trials. Deferred to
# the end of tools/CMakeLists.txt because pool_tools is defined by sim.cmake.
function(pool_fit_setup)
  if(NOT TARGET pool_tools)
    return()
  endif()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(GSL IMPORTED_TARGET gsl)
  if(NOT GSL_FOUND)
    message(STATUS "pool-fit not built (needs GSL: libgsl-dev, installed by tools/setup.sh)")
    return()
  endif()
  find_package(Threads REQUIRED)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/fit/*.c)
  add_library(pool_fit_core STATIC ${sources})
  target_include_directories(pool_fit_core PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(pool_fit_core PUBLIC pool_tools PkgConfig::GSL Threads::Threads m)
  add_executable(pool-fit ${CMAKE_CURRENT_SOURCE_DIR}/pool_fit.c)
  target_link_libraries(pool-fit PRIVATE pool_fit_core)
  # pool-tracks: a camera's tracks of a simulated shot (with noise), pool-fit's input from known values.
  add_executable(pool-tracks ${CMAKE_CURRENT_SOURCE_DIR}/pool_tracks.c)
  target_link_libraries(pool-tracks PRIVATE pool_fit_core)
  # pool-fit-trials: seeded synthetic trials, the coverage of pool-fit's intervals (tests, measurements).
  add_executable(pool-fit-trials ${CMAKE_CURRENT_SOURCE_DIR}/fit_trials.c)
  target_link_libraries(pool-fit-trials PRIVATE pool_fit_core)
  install(TARGETS pool-fit pool-tracks RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
cmake_language(DEFER CALL pool_fit_setup)
