# Compiles and runs static_clash.c (a program defining functions named like libpool internals)
# against a static libpool: libpool.a must link and work, since its internal symbols are local.
# Run as: cmake -DCC=cc [-DFLAGS="-fsanitize=..."] -DLIBRARY=libpool.a -DINCLUDE=dir -DWORK_DIR=dir
#               -P check_static_clash.cmake
file(MAKE_DIRECTORY ${WORK_DIR})
get_filename_component(library_name ${LIBRARY} NAME)
set(program ${WORK_DIR}/static_clash)
file(REMOVE ${program})
separate_arguments(flags UNIX_COMMAND "${FLAGS}")
execute_process(COMMAND ${CC} -std=c11 ${flags} -I${INCLUDE} ${CMAKE_CURRENT_LIST_DIR}/static_clash.c ${LIBRARY}
                        -lm -o ${program}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "a program defining pool_collide, pool_error_set and pool_predict_ball_ball "
                      "does not link with ${library_name}:\n${out}")
endif()
execute_process(COMMAND ${program} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "static_clash linked with ${library_name} failed (${rc}): ${out}")
endif()
message(STATUS "${out}")
