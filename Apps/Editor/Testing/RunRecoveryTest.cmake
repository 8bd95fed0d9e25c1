# A recovered autosave is untitled: Ctrl+S asks where to save it (answered
# SAVED), and the normal exit then deletes the recovery file. Before, the
# recovered volume was the recovery file's document: Ctrl+S wrote into
# recovery.lvdv without asking and the exit deleted that file, the work with it.
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(REMOVE "${SAVED}")
# the autosave a crashed session left: the 64^3 sphere canvas
execute_process(COMMAND "${EDITOR}" --new 64 --fill sphere --size ${SIZE} --no-recovery --autosave 0
  --save "${DIR}/recovery.lvdv" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "writing the recovery file failed (${rc})")
endif ()
execute_process(COMMAND "${EDITOR}" --recovery-dir "${DIR}" --recovery-answer yes --size ${SIZE} --autosave 0
  --keys-after Ctrl+S --save-as-answer "${SAVED}" --quit RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "lvdif-editor failed (${rc})")
endif ()
if (NOT EXISTS "${SAVED}")
  message(FATAL_ERROR "Ctrl+S after recovering did not ask where to save (${SAVED} is missing)")
endif ()
if (EXISTS "${DIR}/recovery.lvdv")
  message(FATAL_ERROR "the normal exit kept the recovery file")
endif ()
execute_process(COMMAND "${CHECK}" --sphere "${SAVED}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "the saved volume is not the recovered one (${rc})")
endif ()
