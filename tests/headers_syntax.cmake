# Every public header compiles on its own with only the flags of compile_flags.txt (what an
# editor or clangd uses in a fresh clone, before any build), warnings as errors.
# -DSOURCE_DIR=... -DCLANGXX=... -P headers_syntax.cmake
file(STRINGS ${SOURCE_DIR}/compile_flags.txt flags)
file(GLOB_RECURSE headers RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/*/include/qmotion/*.hpp)
list(LENGTH headers n)
if(n LESS 40)
  message(FATAL_ERROR "found only ${n} public headers under */include/qmotion")
endif()
set(failed "")
foreach(h IN LISTS headers)
  execute_process(COMMAND ${CLANGXX} ${flags} -Werror -Wno-pragma-once-outside-header
                          -fsyntax-only ${h}
    WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(rc)
    message("${h}:\n${err}")
    list(APPEND failed ${h})
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "headers that do not compile with compile_flags.txt alone: ${failed}")
endif()
message(STATUS "${n} public headers compile with compile_flags.txt alone")
