#!/usr/bin/env bash
# `tarn view --msaa`: the window's anti-aliasing keeps the picture's
# brightness (a world is drawn linear into the multisampled target and the
# resolve into the sRGB window encodes it, as the draws into the window
# did), and changes only edges: the same paused frame with --msaa 1 and 4
# agrees on average within a level and pixel for pixel away from edges.
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
command -v python3 >/dev/null || { echo "skip: python3 is missing (reads the PNGs)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
for m in 1 4; do
    rm -f "window-msaa-$m.png"
    printf 'pause 1\nwindow 760 240\nframes 3\nscreenshot window-msaa-%s.png\nquit\n' $m > "window-msaa-$m.script"
    xvfb-run -a -s "-screen 0 1280x800x24" "$bin" view "$src/scenes/lake.glib" --pack basic --time 1 \
        --msaa $m --script "window-msaa-$m.script" > "window-msaa-$m.log" 2>&1 || { cat "window-msaa-$m.log"; fail "tarn view --msaa $m"; }
    [ -s "window-msaa-$m.png" ] || fail "no window-msaa-$m.png"
done
PYTHONPATH="$src/tests" python3 - <<'PY' || fail "the anti-aliased window differs beyond its edges"
import sys, struct, zlib
import png_probe as p

def read(path):
    data = open(path, "rb").read()
    idat = b""
    for kind, body in p.chunks(data):
        if kind == b"IHDR":
            w, h = struct.unpack(">II", body[:8]); bpp = {2: 3, 6: 4}[body[9]]
        elif kind == b"IDAT":
            idat += body
    return w, h, bpp, p.unfilter(zlib.decompress(idat), w, h, bpp)

w, h, bpp, a = read("window-msaa-1.png")
_, _, _, b = read("window-msaa-4.png")
x0 = 460   # right of the panel: the scene
sa = sb = n = changed = 0
for y in range(h):
    for x in range(x0, w):
        for k in range(3):
            va, vb = a[y][x * bpp + k], b[y][x * bpp + k]
            sa += va; sb += vb; n += 1
            changed += abs(va - vb) > 24
mean_a, mean_b = sa / n, sb / n
print("mean level %.2f without MSAA, %.2f with; %.2f%% of values moved more than 24 levels" % (mean_a, mean_b, 100.0 * changed / n))
if abs(mean_a - mean_b) > 1.0: sys.exit("brightness changed")
if changed == 0: sys.exit("no edge changed: is MSAA on in the window?")
if changed > 0.05 * n: sys.exit("more than edges changed")
PY
echo "window msaa test: ok"
