# libpool.so and libpool.a must define, as global symbols, exactly the functions its public
# headers declare with POOL_API: no internal symbol leaks (users could come to depend on it, or
# clash with it in a static link), no public one is missing.
# Run as: cmake -DNM=nm -DLIBRARY=libpool.so|libpool.a -DHEADERS=dir [-DEXPECT_LEAK=name]
#               [-DMIN_DECLARED=n] -P check_exports.cmake
# A shared library is read with `nm -D` (its dynamic symbol table), an archive (.a) with
# `nm -g` (the global symbols of every member). Every defined global symbol counts, functions
# (T), data (D, B, R), weak (W, V) and the rest, except names reserved to the toolchain (a
# leading underscore: _init, _edata...).
# With EXPECT_LEAK, the check must find that symbol leaked (a test that the check can fail,
# run on the internal archive): it passes only then.
if(LIBRARY MATCHES "\\.a$")
  set(nm_args -g --defined-only)
  set(kind "the static archive")
else()
  set(nm_args -D --defined-only)
  set(kind "the shared library")
endif()
execute_process(COMMAND ${NM} ${nm_args} ${LIBRARY}
  OUTPUT_VARIABLE nm_out RESULT_VARIABLE nm_status)
if(NOT nm_status EQUAL 0)
  message(FATAL_ERROR "${NM} failed on ${LIBRARY}")
endif()
get_filename_component(library_name ${LIBRARY} NAME)
set(exported "")
string(REPLACE "\n" ";" nm_lines "${nm_out}")
foreach(line IN LISTS nm_lines)
  # "ADDRESS TYPE NAME", TYPE upper case for global symbols (U, undefined, is not listed with
  # --defined-only), i for GNU indirect functions, v and w for weak ones. Archive member headers
  # ("member.o:") and blank lines do not match.
  if(line MATCHES "^[0-9a-fA-F]* *([A-TV-Ziuvw]) ([^ ]+)$")
    set(symbol ${CMAKE_MATCH_2})
    if(NOT symbol MATCHES "^_")
      list(APPEND exported ${symbol})
    endif()
  endif()
endforeach()
list(REMOVE_DUPLICATES exported)

set(declared "")
file(GLOB headers ${HEADERS}/*.h)
foreach(header IN LISTS headers)
  file(READ ${header} text)
  string(REGEX MATCHALL "POOL_API[^;{]*[ *](pool_[a-z0-9_]+)\\(" decls "${text}")
  foreach(decl IN LISTS decls)
    string(REGEX MATCH "(pool_[a-z0-9_]+)\\($" name "${decl}")
    list(APPEND declared ${CMAKE_MATCH_1})
  endforeach()
endforeach()

list(SORT exported)
list(SORT declared)
list(LENGTH declared count)
if(NOT DEFINED MIN_DECLARED) # fewer means the headers were not read right
  set(MIN_DECLARED 20)
endif()
if(count LESS MIN_DECLARED)
  message(FATAL_ERROR "found only ${count} POOL_API declarations in ${HEADERS}")
endif()
set(leaked ${exported})
list(REMOVE_ITEM leaked ${declared})
set(missing ${declared})
if(exported)
  list(REMOVE_ITEM missing ${exported})
endif()

if(DEFINED EXPECT_LEAK)
  list(FIND leaked ${EXPECT_LEAK} found)
  if(found LESS 0)
    message(FATAL_ERROR "the check did not find ${EXPECT_LEAK} leaked from ${library_name} "
                        "(leaked: [${leaked}])")
  endif()
  list(LENGTH leaked leak_count)
  message(STATUS "the check finds ${leak_count} internal symbols in ${library_name}, "
                 "${EXPECT_LEAK} among them")
  return()
endif()
if(leaked OR missing)
  message(FATAL_ERROR "${library_name} (${kind}) defines internal global symbols: [${leaked}]; "
                      "public functions not defined: [${missing}]")
endif()
message(STATUS "${library_name} (${kind}) defines exactly the ${count} POOL_API functions as "
               "global symbols")
