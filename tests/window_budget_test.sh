#!/usr/bin/env bash
# The view window's frame budget under Xvfb (ui/res_budget, issue #15):
#   - a still picture is drawn full once it has settled (its first frame
#     is reduced: test_res_budget; here the first frame's wall time, which
#     a loaded machine stretches past the settle time, would decide);
#   - while the camera turns, the scene is drawn below full resolution (a
#     budget of 0.001 ms: every frame is over it, whatever the machine's
#     speed, so no timing decides the outcome);
#   - once the camera stops, a full-resolution frame is drawn and kept, and
#     it is the same picture, pixel for pixel, as a frame drawn with the
#     budget off (the sRGB canvas encodes as the window did);
#   - with the clock running (the script's `play 1`: a script's clock
#     stands otherwise) the picture of water with a wave keeps changing,
#     so it stays reduced past the settle time; calm water reads no clock
#     (no program has a wave model), so it is still and drawn full;
#   - compare-view reduces its packs' images the same way.
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
command -v python3 >/dev/null || { echo "skip: python3 is missing (reads the PNGs)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
scratch=$PWD/window-budget-test
rm -rf "$scratch" && mkdir -p "$scratch" || fail "no scratch directory"
xvfb() { xvfb-run -a -f "$scratch/Xauthority" -s "-screen 0 1280x800x24" "$@"; }
# view_run NAME GLIB: tarn view of GLIB driven by $scratch/NAME.script, its
# log printed; fails when it exits non-zero or an expect-resolution failed
view_run() {
    xvfb "$bin" view "$2" --pack basic --size 900x300 --script "$scratch/$1.script" > "$scratch/$1.log" 2>&1
    local rc=$?
    cat "$scratch/$1.log"
    [ "$rc" -eq 0 ] || fail "tarn view ($1) exited $rc"
    grep -q "FAILED" "$scratch/$1.log" && fail "an expect-resolution of $1.script failed"
    return 0
}

cat > "$scratch/view.script" <<SCRIPT
pause 1
frames 2
wait 0.6
frames 2
expect-resolution full
budget 0.001
orbit 0.02 0 100000
frames 3
expect-resolution reduced
screenshot $scratch/moving.png
frames 1
expect-resolution reduced
orbit 0 0 1
wait 0.6
frames 2
expect-resolution full
screenshot $scratch/still.png
budget 0
reload
frames 1
expect-resolution full
screenshot $scratch/nobudget.png
budget 0.001
pause 0
play 1
wait 0.6
expect-resolution reduced
quit
SCRIPT
# the box over water with a wave (calm water reads no clock: below)
{ cat "$src/tests/data/raymarch/box.glib"; echo "WaveSine 30 2.0 0.02 0 0"; } > "$scratch/box_wave.glib"
view_run view "$scratch/box_wave.glib"
# the moving frame's line says which size it had: below 460x300
grep -E "^tarn: resolution [0-9]+x[0-9]+ \([0-9]+%\) of 460x300" "$scratch/view.log" |
    grep -v "(100%)" | grep -q . || fail "no reduced resolution reported while the camera turned"
for f in moving still nobudget; do   # the window's size, whatever was drawn
    out=$(python3 "$src/tests/png_probe.py" "$scratch/$f.png") || fail "cannot read $f.png"
    echo "$out" | grep -qx "size 900 300" || fail "$f.png is not the window's full size: $out"
done
# the scene area (right of the 440 px panel): the kept frame is the budget-off frame
python3 "$src/tests/png_compare.py" "$scratch/still.png" "$scratch/nobudget.png" 440 ||
    fail "the still frame differs from a frame drawn with the budget off"

# the same box over calm water: with no wave nothing reads the clock (the
# programs are built with the world's wave models only), so with the
# clock running the picture is still, drawn full and kept
cat > "$scratch/calm.script" <<SCRIPT
budget 0.001
pause 0
play 1
wait 0.6
frames 2
expect-resolution full
quit
SCRIPT
view_run calm "$src/tests/data/raymarch/box.glib"

# compare-view: the same budget over its packs
cat > "$scratch/compare.script" <<SCRIPT
frames 2
budget 0.001
orbit 0.02 0 100000
frames 3
expect-resolution reduced
orbit 0 0 1
wait 0.6
frames 2
expect-resolution full
quit
SCRIPT
xvfb "$bin" compare-view "$src/tests/data/raymarch/box.glib" --packs basic,basic --size 400x200 \
    --script "$scratch/compare.script" > "$scratch/compare.log" 2>&1
rc=$?
cat "$scratch/compare.log"
[ "$rc" -eq 0 ] || fail "tarn compare-view exited $rc"
echo "window budget test: ok"
