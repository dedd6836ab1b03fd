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
echo "window shot test: ok"
