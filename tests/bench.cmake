# The comparison features (issue 7): `tarn compare-view` under Xvfb.
# test_bench.c (tarn bench end to end) and test_hard_cases.c are test_*.c
# files like any other.

add_test(NAME compare_view_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/compare_view_test.sh $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(compare_view_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300 LABELS "window;gl")

# A still compare-view window shows the heat maps when the worker has them,
# with no input to wake it (it slept through the job's end).
add_test(NAME compare_view_heat_xvfb
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_py_test.sh compare_view_heat $<TARGET_FILE:tarn> ${CMAKE_SOURCE_DIR}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(compare_view_heat_xvfb PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 180 LABELS "window;gl")
