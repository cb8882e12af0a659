# Runs `${PROGRAM} ${ARG1} ${ARG2} ... ${ARG8}` (unset ones left out) and checks that it fails
# the way a user is promised: exit code ${CODE}, nothing on stdout, exactly one line on stderr,
# matching ${MATCH}.
execute_process(COMMAND ${PROGRAM} ${ARG1} ${ARG2} ${ARG3} ${ARG4} ${ARG5} ${ARG6} ${ARG7} ${ARG8}
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL CODE)
  message(FATAL_ERROR "exit code ${code}, expected ${CODE}; stderr: ${err}")
endif()
if(NOT out STREQUAL "")
  message(FATAL_ERROR "stdout should be empty, got: ${out}")
endif()
string(REGEX MATCHALL "\n" newlines "${err}")
list(LENGTH newlines lines)
if(NOT lines EQUAL 1 OR NOT err MATCHES "\n$")
  message(FATAL_ERROR "stderr should be one line, got ${lines}: ${err}")
endif()
if(NOT err MATCHES "${MATCH}")
  message(FATAL_ERROR "stderr does not match '${MATCH}': ${err}")
endif()
message(STATUS "ok: ${err}")
