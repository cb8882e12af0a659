# Runs `${PROGRAM} ARGS...` (ARGS separated by '|') with the dynamic loader reporting every
# library it opens (LD_DEBUG=files) and checks, by the library's file name: LOADED is among
# them, or NOT_LOADED is not. Exit code 0 expected.
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env LD_DEBUG=files ${PROGRAM} ${args}
                RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "exit code ${code}, expected 0; stderr: ${err}")
endif()
string(REGEX MATCHALL "file=[^ \t\n]+" opened "${err}")
list(REMOVE_DUPLICATES opened)
# Without the loader's list (LD_DEBUG ignored, as in a secure-execution process) nothing is proven.
if(NOT opened MATCHES "libc\\.so")
  message(FATAL_ERROR "the loader listed no libraries (LD_DEBUG=files ignored?): ${err}")
endif()
if(LOADED AND NOT opened MATCHES "${LOADED}")
  message(FATAL_ERROR "${LOADED} was not loaded; loaded: ${opened}")
endif()
if(NOT_LOADED AND opened MATCHES "${NOT_LOADED}")
  message(FATAL_ERROR "${NOT_LOADED} was loaded; loaded: ${opened}")
endif()
message(STATUS "ok: ${opened}")
