# Tests that run the tarn program itself.

# glslang validation of every pack and scene (what CI checks).
add_test(NAME validate_all COMMAND tarn validate WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
set_tests_properties(validate_all PROPERTIES LABELS unit)
# ...and of the built-in world's own stages (world.*, world_height.*), which
# no pack's glib names: tarn builds them itself.
add_test(NAME validate_common COMMAND tarn validate packs/common WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
set_tests_properties(validate_common PROPERTIES LABELS unit)

# The interactive window under Xvfb with a scripted slider change.
add_test(NAME window_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "window;gl")

# Screenshots are opaque and say where they went; the panel follows the window.
add_test(NAME window_shot_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_shot_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_shot_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "window;gl")

# The view window switches packs live; a glman scene refuses one.
add_test(NAME window_pack_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_pack_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_pack_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "window;gl")

# The view window's Setting combo (`setting NAME`, --setting) and its recording.
add_test(NAME window_setting_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_setting_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_setting_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600 LABELS "window;gl;slow")

# `tarn render --setting NAME` draws the row's `--set`s; a session's
# `setting NAME` replays as its assignments do.
add_test(NAME setting_cli
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/setting_cli_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(setting_cli PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "gl;slow")

# The one window loop (ui/app.c) through view and compare-view: hot reload
# with a dependency in a directory made later, and a lost context.
add_test(NAME window_app_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_app_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_app_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "window;gl")

# `cmake --install` into a temporary prefix; the installed tarn, from outside
# the source tree, renders an installed scene with the prefix's packs
# (tests/install_test.sh says how it proves that).
add_test(NAME install_prefix
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/install_test.sh ${CMAKE_COMMAND} ${CMAKE_BINARY_DIR} ${CMAKE_SOURCE_DIR})
set_tests_properties(install_prefix PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS gl)

# Recording a session in the window (Shift+R, --record) and replaying it.
add_test(NAME window_record_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_record_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_record_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "window;gl;slow")

# `tarn record` to an mp4 through ffmpeg: the frame count (ffprobe).
add_test(NAME record_mp4
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/record_mp4_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(record_mp4 PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS gl)

# The frame budget: reduced resolution while the camera moves, the full
# frame once it stops (view and compare-view; ui/res_budget).
add_test(NAME window_budget_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_budget_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_budget_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "window;gl")
# The window anti-aliases (--msaa) without changing the picture's brightness.
add_test(NAME window_msaa_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_msaa_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_msaa_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "window;gl")

# A still window sleeps instead of drawing the same frame; a key wakes it;
# Q quits at once (issue #30).
add_test(NAME window_idle_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_py_test.sh window_idle $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_idle_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "window;gl")

# At 2 fps a press that starts over the panel never reaches the camera
# (issue #30: it dragged a slider and orbited the camera too).
add_test(NAME window_input_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_py_test.sh window_input $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_input_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "window;gl")

# The window's hand-in sheet: a slider's right-click menu (the script's
# `sheet P.NAME`) writes `tarn sheet`'s image of it (issue #27).
add_test(NAME window_sheet_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_sheet_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(window_sheet_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "window;gl")
