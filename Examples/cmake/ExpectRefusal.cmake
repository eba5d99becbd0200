# Runs a command that must refuse its arguments: it must exit with a non-zero code (not a crash)
# and print a message matching EXPECT. Used by the examples' refusal tests:
#   cmake -DEXPECT=<regex> -DCOMMAND=<program|argument|...> -P ExpectRefusal.cmake
if (NOT DEFINED EXPECT OR NOT DEFINED COMMAND)
  message(FATAL_ERROR "ExpectRefusal.cmake needs -DEXPECT=<regex> and -DCOMMAND=<command>")
endif ()
string(REPLACE "|" ";" _command "${COMMAND}")
execute_process(
  COMMAND ${_command}
  RESULT_VARIABLE _result
  OUTPUT_VARIABLE _output
  ERROR_VARIABLE _output)
message("${_output}")
if (NOT _result MATCHES "^[0-9]+$")
  message(FATAL_ERROR "The command did not exit normally: ${_result}")
elseif (_result EQUAL 0)
  message(FATAL_ERROR "The command accepted what it should refuse (exit code 0).")
elseif (NOT _output MATCHES "${EXPECT}")
  message(FATAL_ERROR "Exit code ${_result}, but no message matching '${EXPECT}'.")
endif ()
