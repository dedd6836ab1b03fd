#!/usr/bin/env bash
# At 2 fps a press over the panel never reaches the camera (issue #30).
# The input and the checking are window_input_test.py's.
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
command -v python3 >/dev/null || { echo "skip: python3 is missing"; exit 77; }
scratch=$PWD/window-input-test
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
xvfb-run -a -f "$scratch/Xauthority" -s "-screen 0 1280x800x24" python3 "$src/tests/window_input_test.py" "$bin" "$src"
