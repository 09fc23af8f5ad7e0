# Fails when clang-format (.clang-format at the top) would change any C++ file git tracks.
execute_process(COMMAND git ls-files "*.cpp" "*.hpp" WORKING_DIRECTORY ${SOURCE_DIR}
  OUTPUT_VARIABLE files OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
if(rc)
  message(STATUS "not a git checkout: format check skipped")
  return()
endif()
string(REPLACE "\n" ";" files "${files}")
execute_process(COMMAND ${CLANG_FORMAT} --dry-run -Werror ${files} WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "clang-format would change the files listed above: run clang-format -i on them")
endif()
