# Runs one vplkit command line and checks its exit code and that its output matches a pattern.
#   cmake -DCOMMAND="<program>;<args...>" -DEXPECT_EXIT=<code> -DEXPECT_OUTPUT=<regex>
#         [-DFORBID_FILE=<path>] [-DFORBID_OUTPUT=<regex>] -P expect_exit.cmake
# FORBID_FILE: a file the command must not leave behind (no partial output on failure).
# FORBID_OUTPUT: a pattern the output must not match (e.g. a line printed twice).
if(FORBID_FILE)
  file(REMOVE "${FORBID_FILE}")
endif()
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
set(all "${out}${err}")
if(NOT code STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "expected exit ${EXPECT_EXIT}, got '${code}'. Output:\n${all}")
endif()
if(NOT all MATCHES "${EXPECT_OUTPUT}")
  message(FATAL_ERROR "output does not match '${EXPECT_OUTPUT}':\n${all}")
endif()
if(FORBID_OUTPUT AND all MATCHES "${FORBID_OUTPUT}")
  message(FATAL_ERROR "output matches '${FORBID_OUTPUT}', which it must not:\n${all}")
endif()
if(FORBID_FILE AND EXISTS "${FORBID_FILE}")
  message(FATAL_ERROR "the command left ${FORBID_FILE} behind")
endif()
