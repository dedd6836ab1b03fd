#!/usr/bin/env bash
# The view window's hand-in sheet (issue #27): the script's `sheet P.NAME`
# does what a slider's right-click "Hand-in sheet" does: `tarn sheet` in a
# child with the window's values, and the sheet is written (a PNG as wide
# as five tiles), while the window keeps its own slider value.
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
scratch=$PWD/window-sheet-test
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || fail "no scratch directory"
cat > sheet.script <<'SCRIPT'
frames 2
set BasicWater uOpacity 0.8
frames 1
sheet BasicWater.uOpacity
frames 1
expect BasicWater uOpacity 0.8
quit
SCRIPT
xvfb-run -a -f "$scratch/Xauthority" -s "-screen 0 1280x800x24" "$bin" view "$src/scenes/lake.glib" --pack basic \
    --size 320x180 --script sheet.script >sheet.log 2>&1
rc=$?
cat sheet.log
[ "$rc" -eq 0 ] || fail "tarn view exited $rc"
grep -q "making a hand-in sheet of BasicWater.uOpacity (5 values)" sheet.log || fail "the sheet was not started"
out=$(sed -n 's/.*sheet written: //p' sheet.log)
[ -n "$out" ] && [ -s "$out" ] || fail "no sheet written"
read -r _ w h < <(python3 "$src/tests/png_probe.py" "$out" | grep '^size ')
echo "sheet $out: ${w}x$h"
[ "${w:-0}" -gt "$((4 * ${h:-1}))" ] || fail "the sheet (${w}x$h) is not five tiles side by side"
echo "window sheet test: ok"
