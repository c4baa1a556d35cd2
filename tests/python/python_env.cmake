# The interpreter and environment of the Python tests (tests/python, tests/python_dask): the
# project's .venv (tools/setup.sh), else python3; libpool.so and python/ on the paths. In the
# sanitizer build the interpreter is not instrumented, so the compiler's ASan runtime is preloaded
# into it (the worker processes of Dask inherit it): then libpool.so's checks see every use of C
# memory that the binding makes (leak detection off, as the interpreter's own allocations would be
# reported). Sets POOL_PY_TEST_PYTHON and POOL_PY_ENV, and POOL_PY_SKIP (the reason) when the
# sanitizer build has no runtime to preload.
function(pool_python_test_env)
  if(EXISTS ${CMAKE_SOURCE_DIR}/.venv/bin/python)
    set(python ${CMAKE_SOURCE_DIR}/.venv/bin/python)
  else()
    find_program(POOL_PY_TEST_PYTHON_FOUND NAMES python3 REQUIRED)
    set(python ${POOL_PY_TEST_PYTHON_FOUND})
  endif()
  set(env LIBPOOL_PATH=$<TARGET_FILE:pool_shared> PYTHONPATH=${CMAKE_SOURCE_DIR}/python)
  if(TARGET pool_scenario_shared) # libpool.batch's parser and shots
    list(APPEND env LIBPOOL_SCENARIO_PATH=$<TARGET_FILE:pool_scenario_shared>)
  endif()
  set(skip "")
  if(POOL_SANITIZE)
    set(runtime "")
    if(CMAKE_C_COMPILER_ID STREQUAL "GNU")
      execute_process(COMMAND ${CMAKE_C_COMPILER} -print-file-name=libasan.so
                      OUTPUT_VARIABLE runtime OUTPUT_STRIP_TRAILING_WHITESPACE)
    endif()
    if(NOT IS_ABSOLUTE "${runtime}" OR NOT EXISTS "${runtime}")
      set(skip "skipped in the sanitizer build (no ASan runtime to preload)")
    else()
      list(APPEND env LD_PRELOAD=${runtime} ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
           UBSAN_OPTIONS=print_stacktrace=1)
    endif()
  endif()
  set(POOL_PY_TEST_PYTHON ${python} PARENT_SCOPE)
  set(POOL_PY_ENV ${env} PARENT_SCOPE)
  set(POOL_PY_SKIP "${skip}" PARENT_SCOPE)
endfunction()
