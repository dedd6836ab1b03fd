#!/usr/bin/env bash
# `tarn view`'s screenshots under Xvfb: opaque (alpha 255 everywhere, not
# what the panel's blending left in the window's alpha), announced with an
# absolute path, and after the window grows the panel still reaches its
# bottom (its height follows the window).
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
command -v python3 >/dev/null || { echo "skip: python3 is missing (reads the PNGs)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
probe() { python3 "$src/tests/png_probe.py" "$@"; }
rm -f window-shot.png window-shot-big.png
xvfb-run -a -s "-screen 0 1280x800x24" "$bin" view "$src/tests/data/window/shot.glib" \
    --script "$src/tests/data/window/shot.script" 2>&1 | tee window-shot-test.log
rc=${PIPESTATUS[0]}
[ "$rc" -eq 0 ] || fail "tarn view exited $rc"
for f in window-shot.png window-shot-big.png; do
    [ -s "$f" ] || fail "no $f"
    grep -q "^tarn: screenshot /.*/$f\$" window-shot-test.log || fail "$f is not announced with an absolute path"
    probe "$f" | grep -qx "alpha_min 255" || fail "$f is not opaque: $(probe "$f" | grep alpha_min)"
done
out=$(probe window-shot-big.png 20 625) || fail "cannot read window-shot-big.png"
echo "$out"
echo "$out" | grep -qx "size 900 640" || fail "the window did not grow to 900 x 640"
# 10 px above the bottom, left: the panel's background (~16), not the clear colour (31 31 33)
r=$(echo "$out" | awk '$1 == "pixel" { print $4 }')
[ "$r" -lt 25 ] || fail "the panel does not reach the bottom of the grown window (red $r there)"
echo "window shot test (script): ok"

# P (a key, not the script) writes tarn-DATE-N.png in the current
# directory, opaque, announced with its absolute path; Q then quits.
rm -f tarn-*.png
# inside xvfb-run: the window in the background, the keys, then both exit codes
keys_run='
    "$1" view "$2/tests/data/window/shot.glib" --script "$2/tests/data/window/keys.script" &
    view=$!
    sleep 1
    python3 "$2/tests/x_keys.py" "tarn-*.png" p q
    keys=$?
    wait $view
    view_rc=$?
    [ "$keys" -eq 77 ] && exit 77
    [ "$keys" -eq 0 ] && [ "$view_rc" -eq 0 ]'
xvfb-run -a -s "-screen 0 1280x800x24" bash -c "$keys_run" keys_run "$bin" "$src" 2>&1 | tee window-keys-test.log
rc=${PIPESTATUS[0]}
[ "$rc" -eq 77 ] && { echo "window shot test: ok (the key run skipped: no libXtst)"; exit 0; }
[ "$rc" -eq 0 ] || fail "the P key run failed ($rc)"
shot=$(ls tarn-*.png 2>/dev/null | head -1)
[ -n "$shot" ] || fail "P wrote no tarn-*.png in the current directory"
grep -q "^tarn: screenshot /.*/$shot\$" window-keys-test.log || fail "$shot is not announced with an absolute path"
probe "$shot" | grep -qx "alpha_min 255" || fail "$shot is not opaque"
# the whole frame: the quad's colour (0.2 0.4 0.5) in the scene area, not what the back buffer held before
probe "$shot" 600 100 | grep -qx "pixel 600 100 51 102 128 255" || fail "$shot is not the drawn frame: $(probe "$shot" 600 100 | tail -1)"
echo "window shot test (P key): ok"
