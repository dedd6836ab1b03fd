#!/usr/bin/env bash
# The view window's Setting combo (the script's `setting NAME` does what
# picking NAME does), under Xvfb, on the lake drawn by natural:
#   - a moved slider goes back to the pack's default, and the picture is
#     the one the paper row's assignments give when set one by one;
#   - a recording (--record) notes the switch as `setting paper`;
#   - `--setting paper` opens the window on the same picture;
#   - a setting the pack lacks fails the script, naming the ones it has
#     (basic's: no default row, so the pack's defaults come first).
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
scratch=$PWD/window-setting-test
rm -rf "$scratch" && mkdir -p "$scratch" || fail "no scratch directory"
xvfb() { xvfb-run -a -f "$scratch/Xauthority" -s "-screen 0 1280x800x24" "$@"; }
# 440 px of panel (APP_PANEL_WIDTH) left of a 200x112 scene; the panel's
# frame times differ between runs, so only the scene's pixels are compared
view() { xvfb "$bin" view "$src/scenes/lake.glib" --pack natural --size 640x112 "$@"; }
scene() { python3 "$src/tests/png_probe.py" "$scratch/$1.png" hash 440 | grep '^hash'; }

cat > "$scratch/choose.script" <<SCRIPT
pause 1
time 1
frames 1
screenshot $scratch/default.png
set NaturalWater uReflectDist 3
frames 1
expect NaturalWater uReflectDist 3
setting paper
frames 2
expect NaturalWater uReflectDist 1
screenshot $scratch/setting.png
quit
SCRIPT
view --script "$scratch/choose.script" --record "$scratch/choose.session" >"$scratch/choose.log" 2>&1
rc=$?
cat "$scratch/choose.log"
[ "$rc" -eq 0 ] || fail "tarn view exited $rc"
[ "$(grep -c 'holds the expected value' "$scratch/choose.log")" -eq 2 ] || fail "an expect is missing"
grep -q "^t=[0-9.]* setting paper$" "$scratch/choose.session" || fail "the switch was not recorded"

# the paper row of packs/natural/bench.txt, one assignment at a time
cat > "$scratch/sets.script" <<SCRIPT
pause 1
time 1
frames 1
set NaturalWater CAUSTICS_GPU 0
set NaturalWater EXACT_FRESNEL 0
set NaturalWater BEER_LAMBERT 0
set NaturalWater REFINE_STEPS 0
set NaturalWater uPhotonGrid 512
set NaturalWater uCausticRes 256
set NaturalWater SPECULAR_FRESNEL 0
set NaturalWater uSpecular 0.5
set NaturalWater uShininess 400
frames 2
screenshot $scratch/sets.png
quit
SCRIPT
view --script "$scratch/sets.script" >"$scratch/sets.log" 2>&1 || { cat "$scratch/sets.log"; fail "the --set run failed"; }
cat > "$scratch/open.script" <<SCRIPT
pause 1
time 1
frames 2
screenshot $scratch/open.png
quit
SCRIPT
view --setting paper --script "$scratch/open.script" >"$scratch/open.log" 2>&1 || { cat "$scratch/open.log"; fail "--setting paper failed"; }
for f in default setting sets open; do [ -s "$scratch/$f.png" ] || fail "no $f.png"; done
[ "$(scene setting)" = "$(scene sets)" ] || fail "setting paper draws other pixels than its assignments"
[ "$(scene open)" = "$(scene sets)" ] || fail "--setting paper draws other pixels than its assignments"
[ "$(scene default)" = "$(scene setting)" ] && fail "the picture did not change with the setting"

printf 'frames 1\nsetting nope\nquit\n' > "$scratch/bad.script"
xvfb "$bin" view "$src/scenes/lake.glib" --pack basic --size 200x112 --script "$scratch/bad.script" >"$scratch/bad.log" 2>&1
rc=$?
cat "$scratch/bad.log"
[ "$rc" -ne 0 ] || fail "a setting the pack lacks did not fail the script"
grep -q "basic has no setting 'nope'; it has default exact schlick" "$scratch/bad.log" || fail "no list of the settings"
echo "window setting test: ok"
