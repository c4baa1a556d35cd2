# Installs libpool into a scratch prefix, then builds and runs tiny programs against it as a
# user does: a CMake project through find_package(libpool) (static libpool::pool, pool_games and
# pool_scenario), and the same sources compiled with `cc $(pkg-config --cflags --libs libpool)`
# and `... libpool_scenario` (shared libraries, found at run time through the .pc files' rpath,
# with LD_LIBRARY_PATH unset).
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix --component Unspecified
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer/project -B ${WORK_DIR}/build
  -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the consumer failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the consumer failed: ${rc}")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer RESULT_VARIABLE rc OUTPUT_VARIABLE out)
message(STATUS "find_package: ${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the find_package consumer failed: ${rc}")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer_games RESULT_VARIABLE rc OUTPUT_VARIABLE out)
message(STATUS "find_package: ${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the find_package games consumer failed: ${rc}")
endif()

if(WITH_SCENARIO)
  execute_process(COMMAND ${WORK_DIR}/build/consumer_scenario RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "find_package: ${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the find_package scenario consumer failed: ${rc} ${err}")
  endif()
endif()

# pkg-config, as the README's one-line build does it.
find_program(PKG_CONFIG NAMES pkg-config pkgconf REQUIRED)
file(GLOB_RECURSE pc_files ${WORK_DIR}/prefix/*/libpool.pc)
list(LENGTH pc_files pc_count)
if(NOT pc_count EQUAL 1)
  message(FATAL_ERROR "expected one installed libpool.pc, found: ${pc_files}")
endif()
get_filename_component(pc_dir ${pc_files} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pc_dir})
unset(ENV{LD_LIBRARY_PATH})
execute_process(COMMAND ${PKG_CONFIG} --modversion libpool OUTPUT_VARIABLE version
  OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT version STREQUAL "${PROJECT_VERSION}")
  message(FATAL_ERROR "pkg-config --modversion libpool: '${version}' (expected ${PROJECT_VERSION})")
endif()
# Compiles SOURCE with `cc $(pkg-config --cflags --libs PACKAGE) EXTRA` into NAME and runs it.
function(pool_consumer_pc package source name)
  execute_process(COMMAND ${PKG_CONFIG} --cflags --libs ${package} OUTPUT_VARIABLE flags
    OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pkg-config --cflags --libs ${package} failed")
  endif()
  separate_arguments(flags UNIX_COMMAND "${flags}")
  execute_process(COMMAND ${CC} -std=c11 ${SOURCE_DIR}/tests/consumer/project/${source} ${flags} ${ARGN}
    -o ${WORK_DIR}/${name} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cc with pkg-config's flags for ${package} (${flags}) failed")
  endif()
  execute_process(COMMAND ${WORK_DIR}/${name} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "pkg-config: ${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the pkg-config consumer ${name} failed: ${rc} ${err}")
  endif()
endfunction()

pool_consumer_pc(libpool main.c consumer_pc -lm)
# The scenario library through its own pkg-config file (libpool_scenario.pc requires libpool.pc).
if(WITH_SCENARIO)
  pool_consumer_pc(libpool_scenario scenario.c consumer_scenario_pc)
endif()
