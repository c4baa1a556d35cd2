# pool-sensitivity (tools/pool_sensitivity.c, tools/sensitivity/): noise on a strike, N samples
# of libpool games' noise (pool/noise.h), the clouds of final positions and their statistics
# (GSL). Only this tool links GSL; libpool itself does not. Deferred to the end of tools/CMakeLists.txt because
# pool_scenario is defined by sim.cmake, which is included after this file.
function(pool_sensitivity_setup)
  if(NOT TARGET pool_scenario)
    return()
  endif()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(GSL IMPORTED_TARGET gsl)
  if(NOT GSL_FOUND)
    message(STATUS "pool-sensitivity not built (needs GSL: libgsl-dev, installed by tools/setup.sh)")
    return()
  endif()
  find_package(Threads REQUIRED)
  # The optional models of issue 12 (pool_sim_def.models): named sets mathavan2010, alciatore,
  # endmass... exist only when the library has them.
  include(CheckCSourceCompiles)
  # (Checked afresh at every configure, so a build tree sees the models once they land.)
  unset(POOL_SENS_HAVE_MODELS CACHE)
  set(CMAKE_REQUIRED_INCLUDES ${CMAKE_SOURCE_DIR}/libpool/include)
  set(CMAKE_REQUIRED_QUIET ON)
  check_c_source_compiles("
    #include \"pool/pool.h\"
    int main(void) { pool_sim_def d = {0};
      d.models.cushion = POOL_CUSHION_MATHAVAN2010; return (int)d.models.cushion - 1; }"
    POOL_SENS_HAVE_MODELS)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/sensitivity/*.c)
  add_executable(pool-sensitivity ${CMAKE_CURRENT_SOURCE_DIR}/pool_sensitivity.c ${sources})
  target_include_directories(pool-sensitivity PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(pool-sensitivity PRIVATE pool_scenario PkgConfig::GSL Threads::Threads m)
  if(POOL_SENS_HAVE_MODELS)
    target_compile_definitions(pool-sensitivity PRIVATE POOL_SENS_HAVE_MODELS=1)
  endif()
  install(TARGETS pool-sensitivity RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
cmake_language(DEFER CALL pool_sensitivity_setup)
