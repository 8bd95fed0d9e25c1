# Runs lvdif-editor with ARGS that it must refuse: a non-zero exit (not a
# crash: a signal gives a text status) and EXPECT in its output.
execute_process(COMMAND "${EDITOR}" ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if (rc EQUAL 0 OR NOT rc MATCHES "^[0-9]+$")
  message(FATAL_ERROR "lvdif-editor should have exited with an error status, got '${rc}'")
endif ()
if (NOT "${out}${err}" MATCHES "${EXPECT}")
  message(FATAL_ERROR "the message '${EXPECT}' is missing")
endif ()
