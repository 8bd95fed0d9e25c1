# Runs the checker with PREP first if given (e.g. to write an input mesh),
# the editor with ARGS (and again with ARGS2 if given), then the checker
# with CHECKS; fails if any fails.
# PARAMS: the test's keywords (set() commands written by lvdif_editor_test)
if (DEFINED PARAMS)
  include("${PARAMS}")
endif ()
if (DEFINED CONTENT_FILE)
  file(REMOVE "${CONTENT_FILE}")
endif ()
# run_step(WHAT COMMAND ...): runs the command, prints its output and fails
# naming WHAT if its status is not 0; its output is left in step_output.
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc})")
  endif ()
  set(step_output "${out}${err}" PARENT_SCOPE)
endfunction()
if (DEFINED PREP)
  run_step("preparation" "${CHECK}" ${PREP})
endif ()
run_step("lvdif-editor" "${EDITOR}" ${ARGS})
# EXPECT_OUTPUT / REFUSE_OUTPUT: a regular expression the editor's output must / must not match
include("${CMAKE_CURRENT_LIST_DIR}/CheckOutput.cmake")
check_output("${step_output}")
if (DEFINED ARGS2)
  run_step("second lvdif-editor run" "${EDITOR}" ${ARGS2}) # e.g. reopening what the first saved
endif ()
# CONTENT_FILE / CONTENT: a text file the run wrote and a regular expression its text must match
if (DEFINED CONTENT_FILE)
  if (NOT EXISTS "${CONTENT_FILE}")
    message(FATAL_ERROR "${CONTENT_FILE} was not written")
  endif ()
  file(READ "${CONTENT_FILE}" content)
  if (NOT "${content}" MATCHES "${CONTENT}")
    message(FATAL_ERROR "${CONTENT_FILE} does not match '${CONTENT}':\n${content}")
  endif ()
endif ()
if (DEFINED CHECKS)
  run_step("check" "${CHECK}" ${CHECKS})
endif ()
