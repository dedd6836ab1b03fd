#!/usr/bin/env bash
# A still window sleeps (at most 5% of a core) and still answers a key; Q
# ends it at once (issue #30). The measuring is window_idle_test.py's.
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
command -v python3 >/dev/null || { echo "skip: python3 is missing"; exit 77; }
scratch=$PWD/window-idle-test
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
xvfb-run -a -f "$scratch/Xauthority" -s "-screen 0 1280x800x24" python3 "$src/tests/window_idle_test.py" "$bin" "$src"
