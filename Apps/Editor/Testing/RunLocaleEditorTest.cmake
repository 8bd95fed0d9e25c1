# RunEditorTest.cmake under a comma-decimal locale: de_DE.UTF-8, compiled with
# localedef into LOCALE_DIR (CI images carry no locale but C and POSIX), set
# through LOCPATH and LC_ALL for the editor and the checker. Prints SKIP (the
# test's SKIP_REGULAR_EXPRESSION) when the locale cannot be made.
# PARAMS: the test's keywords (set() commands written by lvdif_editor_test)
if (DEFINED PARAMS)
  include("${PARAMS}")
endif ()
file(MAKE_DIRECTORY "${LOCALE_DIR}")
execute_process(COMMAND localedef -i de_DE -f UTF-8 "${LOCALE_DIR}/de_DE.UTF-8"
  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if (NOT EXISTS "${LOCALE_DIR}/de_DE.UTF-8/LC_NUMERIC")
  message("SKIP: localedef could not make the de_DE.UTF-8 locale (${rc})")
  return()
endif ()
set(ENV{LOCPATH} "${LOCALE_DIR}")
set(ENV{LC_ALL} "de_DE.UTF-8")
include("${CMAKE_CURRENT_LIST_DIR}/RunEditorTest.cmake")
