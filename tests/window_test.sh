#!/usr/bin/env bash
# The interactive window under Xvfb: it starts, draws the panel, and a
# scripted slider change changes the uniform in the GL program.
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
rm -f window-test.png
xvfb-run -a -s "-screen 0 1280x800x24" "$bin" view "$src/tests/data/window/scene.glib" \
    --script "$src/tests/data/window/slider.script" 2>&1 | tee window-test.log
rc=${PIPESTATUS[0]}
[ "$rc" -eq 0 ] || { echo "FAIL: tarn view exited $rc"; exit 1; }
grep -q "Flat.uGrey holds the expected value" window-test.log || { echo "FAIL: no expect ran"; exit 1; }
[ "$(grep -c 'holds the expected value' window-test.log)" -eq 2 ] || { echo "FAIL: an expect is missing"; exit 1; }
[ -s window-test.png ] || { echo "FAIL: no screenshot"; exit 1; }
echo "window test: ok"
