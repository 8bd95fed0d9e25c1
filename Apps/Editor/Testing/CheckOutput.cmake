# check_output(TEXT): an editor run's output TEXT must match EXPECT_OUTPUT and
# must not match REFUSE_OUTPUT (regular expressions), each where given.
function(check_output text)
  if (DEFINED EXPECT_OUTPUT AND NOT "${text}" MATCHES "${EXPECT_OUTPUT}")
    message(FATAL_ERROR "lvdif-editor's output does not match '${EXPECT_OUTPUT}'")
  endif ()
  if (DEFINED REFUSE_OUTPUT AND "${text}" MATCHES "${REFUSE_OUTPUT}")
    message(FATAL_ERROR "lvdif-editor's output matches '${REFUSE_OUTPUT}'")
  endif ()
endfunction()
