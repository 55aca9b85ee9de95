# expect_refused(<command...> CASES <case>...): runs <command> <arguments> for each case
# "<arguments>|<expected message>" (the message a regex; no brackets: they would hide the list's
# separators) and fails unless the run ends with a non-zero status, stderr matches the message
# and stdout does not match ${REFUSED_RUN_STARTED} (when set: the sign that a run began).
function(expect_refused)
  cmake_parse_arguments(PARSE_ARGV 0 ER "" "" "CASES")
  foreach(case IN LISTS ER_CASES)
    string(FIND "${case}" "|" bar)
    string(SUBSTRING "${case}" 0 ${bar} arguments)
    math(EXPR bar "${bar} + 1")
    string(SUBSTRING "${case}" ${bar} -1 expected)
    separate_arguments(arguments UNIX_COMMAND "${arguments}")
    execute_process(COMMAND ${ER_UNPARSED_ARGUMENTS} ${arguments} RESULT_VARIABLE rc OUTPUT_VARIABLE log
                    ERROR_VARIABLE err)
    set(started FALSE)
    if(DEFINED REFUSED_RUN_STARTED AND log MATCHES "${REFUSED_RUN_STARTED}")
      set(started TRUE)
    endif()
    if(rc EQUAL 0 OR NOT err MATCHES "${expected}" OR started)
      message(FATAL_ERROR "${arguments}: expected a non-zero status before any run and '${expected}', got (${rc}):\n${log}\n${err}")
    endif()
  endforeach()
endfunction()
