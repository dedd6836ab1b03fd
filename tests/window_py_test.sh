#!/usr/bin/env bash
# Runs one of the window tests written in Python (tests/NAME_test.py: it
# drives the window and does the checking) under a private Xvfb, in a
# scratch folder of its own:  window_py_test.sh NAME TARN SOURCE_DIR
#   window_idle   a still window sleeps (at most 5% of a core), answers a
#                 key, and Q ends it at once (issue #30)
#   window_input  at 2 fps a press over the panel never reaches the camera
#                 (issue #30)
#   compare_view_heat  a still compare-view shows its heat maps when the
#                 worker has them, with no input to wake it
set -u
name=$1; bin=$2; src=$3
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
command -v python3 >/dev/null || { echo "skip: python3 is missing"; exit 77; }
scratch=$PWD/${name//_/-}-test
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
xvfb-run -a -f "$scratch/Xauthority" -s "-screen 0 1280x800x24" python3 "$src/tests/${name}_test.py" "$bin" "$src"
