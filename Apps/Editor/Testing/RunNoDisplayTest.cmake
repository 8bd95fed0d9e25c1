# lvdif-editor without an X display (DISPLAY removed, as over a plain ssh
# login): --help prints the options with their defaults and exits 0; a run that
# needs a window exits 1 with one line that says why and how to run headless.
unset(ENV{DISPLAY})
unset(ENV{WAYLAND_DISPLAY})
unset(ENV{QT_QPA_PLATFORM})
execute_process(COMMAND "${EDITOR}" --help RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("--help: status ${rc}\n${out}${err}")
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "--help without a display should exit 0, got '${rc}'")
endif ()
foreach (expect "--open-mesh <file>" "default[ \n]+128" "default[ \n]+sphere" "--radius <r>" "default[ \n]+3[)]"
    "exit status: 0 done, 1 failed while running [(][^)]*[)], 2 command line refused")
  if (NOT "${out}" MATCHES "${expect}")
    message(FATAL_ERROR "--help does not say '${expect}'")
  endif ()
endforeach ()
# --mesh-resolution says its range (it said none: "Voxels along the mesh's longest
# axis (--open-mesh; default 128)"), and the range said is the one taken: its ends
# pass the options (and then need a window: status 1), one beyond them is refused
# (status 2) in the same numbers.
if (NOT "${out}" MATCHES "--mesh-resolution <n>[ \n]+Voxels along the[ \n]+mesh's[ \n]+longest[ \n]+axis,[ \n]+([0-9]+)[ \n]+to[ \n]+([0-9]+)[ \n]")
  message(FATAL_ERROR "--help does not give the range of --mesh-resolution")
endif ()
set(lo "${CMAKE_MATCH_1}")
set(hi "${CMAKE_MATCH_2}")
math(EXPR below "${lo} - 1")
math(EXPR above "${hi} + 1")
foreach (value_rc "${lo}|1" "${hi}|1" "${below}|2" "${above}|2")
  string(REPLACE "|" ";" value_rc "${value_rc}")
  list(GET value_rc 0 value)
  list(GET value_rc 1 want)
  execute_process(COMMAND "${EDITOR}" --open-mesh no-such-mesh.obj --mesh-resolution ${value} --no-recovery
    --autosave 0 --quit RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  # below the least: the padding's rule, saying why (the range's ends are every fitted grid's, 2 and 1048576)
  if (NOT rc EQUAL want OR (want EQUAL 2 AND NOT "${e}" MATCHES "--mesh-resolution expects an integer in [[]2, ${hi}[]]"
      AND NOT "${e}" MATCHES "--mesh-resolution ${value} leaves no voxel for the mesh inside the 2 voxels of padding on every side: use at least ${lo}"))
    message(FATAL_ERROR "--mesh-resolution ${value}: status ${rc} (want ${want}): ${e}")
  endif ()
endforeach ()
execute_process(COMMAND "${EDITOR}" --new 16 --no-recovery --autosave 0 --quit
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("--new 16 --quit: status ${rc}\n${out}${err}")
if (NOT rc EQUAL 1)
  message(FATAL_ERROR "without a display the editor should exit 1, got '${rc}'")
endif ()
if (NOT "${err}" MATCHES "lvdif-editor: cannot open a window: no usable X display [(]DISPLAY=not set[)]; run it on a desktop, or headless as xvfb-run -a")
  message(FATAL_ERROR "the no-display message is missing")
endif ()
# one line of its own: Qt's platform plugin lines are not repeated
string(REGEX MATCHALL "\n" lines "${err}")
list(LENGTH lines n)
string(FIND "${err}" "qt.qpa" qpa)
if (NOT qpa EQUAL -1 OR n GREATER 2)
  message(FATAL_ERROR "more than the one message (and the CUDA notice) on stderr: '${err}'")
endif ()
# Every option is checked before the QApplication starts: without a display a
# bad option is still its own one line with status 2 (it said "cannot open a
# window" with status 1); Qt's own options (-display NAME, -style NAME) are
# Qt's, taken with their values, and not refused as unknown.
foreach (case "--radius;abc|--radius expects a number, got 'abc'"
    "-display;:12345;-style;fusion;--strength;1.5|--strength must be a finite number in [(]0, 1[]] [(]got 1.5[)]"
    "--bogus|lvdif-editor: Unknown option 'bogus'"
    # a word of --keys that is no key (it failed the run after the volume was made, status 1)
    "--keys;G Bogus|lvdif-editor: --keys: 'Bogus' is not a key"
    "--keys-after;Ctrl+Z,Ctrl+Y|lvdif-editor: --keys-after: 'Ctrl[+]Z,Ctrl[+]Y' is not a key"
    # a number with spaces around it, refused as the CLI's options refuse it (the editor took ' 5' as 5)
    "--radius; 5|lvdif-editor: --radius expects a number, got ' 5' [(]no spaces around the number[)]"
    "--samples;4 |lvdif-editor: --samples expects an integer in [[]0, 16[]], got '4 ' [(]no spaces around the number[)]")
  string(REPLACE "|" ";" case "${case}")
  list(GET case -1 expect)
  list(REMOVE_AT case -1)
  execute_process(COMMAND "${EDITOR}" --new 16 --no-recovery --autosave 0 ${case} --quit
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${case}: status ${rc}\n${out}${err}")
  if (NOT rc EQUAL 2 OR NOT "${err}" MATCHES "${expect}" OR "${err}" MATCHES "cannot open a window")
    message(FATAL_ERROR "without a display '${case}' should be refused with status 2 and '${expect}' alone")
  endif ()
endforeach ()
# A --new whose chunk table alone passes the memory limit is a refused command
# line before the window, in the CLI's words for its --size (it was the canvas's
# own error once Qt had started, naming no option, status 1; without a display,
# the display's error).
execute_process(COMMAND "${EDITOR}" --new 100000 --no-recovery --autosave 0 --quit
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("--new 100000: status ${rc}\n${out}${err}")
if (NOT rc EQUAL 2 OR NOT "${err}" MATCHES "lvdif-editor: --new 100000 makes a canvas of 100000 x 100000 x 100000 voxels, whose chunk table alone needs [0-9.]+ GiB, more than the limit of [^\n]*: use a smaller --new\n$")
  message(FATAL_ERROR "--new 100000 should be refused with status 2 and one line naming --new")
endif ()
execute_process(COMMAND "${EDITOR}" --new "32x 16x16" --no-recovery --autosave 0 --quit
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("--new '32x 16x16': status ${rc}\n${out}${err}")
if (NOT rc EQUAL 2 OR NOT "${err}" MATCHES "lvdif-editor: --new expects N or NXxNYxNZ in whole numbers of voxels, got '32x 16x16' [(]no spaces around the number[)]")
  message(FATAL_ERROR "--new '32x 16x16' should be refused with status 2, as the CLI's --size")
endif ()
# Qt's offscreen platform has no OpenGL for the view: one line and status 1 (the
# first frame crashed the editor, status 139).
execute_process(COMMAND "${EDITOR}" -platform offscreen --new 16 --no-recovery --autosave 0 --quit
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("-platform offscreen: status ${rc}\n${out}${err}")
if (NOT rc EQUAL 1 OR NOT "${err}" MATCHES "lvdif-editor: cannot (draw the view|open a window)")
  message(FATAL_ERROR "-platform offscreen should be refused with status 1 and one line")
endif ()
