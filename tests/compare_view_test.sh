#!/usr/bin/env bash
# `tarn compare-view` under Xvfb: two packs in one window, the first drawn
# before the second loads, a slider of one
# reaches only its own program, the wipe and the heat maps are drawn, and
# each pack's time is reported; a divider drag between two frames moves the
# divider, not the camera.
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
rm -f compare-grid.png compare-wipe.png compare-heat.png
xvfb-run -a -s "-screen 0 1280x800x24" "$bin" compare-view "$src/scenes/lake.glib" --packs basic,basic \
    --size 320x180 --time 1 --ref-caustic-res 32 --ref-photons 4 \
    --script "$src/tests/data/compare_view/compare.script" 2>&1 | tee compare-view-test.log
rc=${PIPESTATUS[0]}
fail() { echo "FAIL: $*"; exit 1; }
[ "$rc" -eq 0 ] || fail "tarn compare-view exited $rc"
[ "$(grep -c 'holds the expected value' compare-view-test.log)" -eq 2 ] || fail "an expect is missing"
grep -q "every pack has a heat map" compare-view-test.log || fail "no heat maps"
# the first pack's picture comes before the second pack is loaded (issue #30 item 7)
first=$(grep -n "first picture at [0-9.]* ms, basic drawn; loading the others" compare-view-test.log | head -1 | cut -d: -f1)
all=$(grep -n "loaded .*lake.glib (2 packs)" compare-view-test.log | head -1 | cut -d: -f1)
[ -n "$first" ] && [ -n "$all" ] && [ "$first" -lt "$all" ] || fail "the first picture did not come before the second pack's load"
[ "$(grep -c 'heat map .*RMSE [0-9.]*, PSNR' compare-view-test.log)" -eq 4 ] || fail "a pack's RMSE is missing"
[ "$(grep -c 'heat map .*; HDR-FLIP map$' compare-view-test.log)" -eq 2 ] || fail "no FLIP maps"
grep -q "1 basic: [0-9.]* ms GPU, [0-9.]* ms wall" compare-view-test.log || fail "no timings for pack 1"
grep -q "2 basic #2: [0-9.]* ms GPU, [0-9.]* ms wall" compare-view-test.log || fail "no timings for pack 2"
for f in compare-grid.png compare-wipe.png compare-heat.png; do [ -s "$f" ] || fail "no $f"; done
# the wipe's divider follows a drag pressed on it, even when the whole drag
# falls between two frames; a drag pressed elsewhere turns the camera
xvfb-run -a -s "-screen 0 1280x800x24" "$bin" compare-view "$src/scenes/lake.glib" --packs basic,basic \
    --size 320x180 --time 1 --script "$src/tests/data/compare_view/drag.script" 2>&1 | tee compare-view-drag.log
[ "${PIPESTATUS[0]}" -eq 0 ] || fail "the drag script failed"
[ "$(grep -c 'expect-divider 0.750: the divider is at 0.750$' compare-view-drag.log)" -eq 2 ] || fail "the divider did not follow"
grep -q "expect-camera home: the camera is home$" compare-view-drag.log || fail "the divider drag turned the camera"
grep -q "expect-camera moved: the camera is moved$" compare-view-drag.log || fail "a drag on the view did not turn the camera"
echo "compare-view test: ok"
