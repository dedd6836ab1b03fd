#!/usr/bin/env bash
# The view window switches packs live (the panel's Pack combo; the script's
# `pack NAME` does the same), under Xvfb:
#   - the lake opens with its own pack (raymarch); switching to natural links
#     natural's program (its slider's default holds), and the picture
#     changes; switching back links raymarch's program again; a recording
#     (--record) notes both switches;
#   - a plain glman scene (no world) refuses a pack: the load fails with
#     the reason, the scene stays on screen (its program still linked), and
#     a later reload loads it as it is (the refused pack is not kept).
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
scratch=$PWD/window-pack-test
rm -rf "$scratch" && mkdir -p "$scratch" || fail "no scratch directory"
xvfb() { xvfb-run -a -f "$scratch/Xauthority" -s "-screen 0 1280x800x24" "$@"; }

cat > "$scratch/switch.script" <<SCRIPT
frames 1
expect RaymarchWater uMaxIter 40
screenshot $scratch/raymarch.png
pack natural
frames 1
expect NaturalWater uReflectDist 1
screenshot $scratch/natural.png
pack raymarch
frames 1
expect RaymarchWater uMaxIter 40
quit
SCRIPT
xvfb "$bin" view "$src/scenes/lake.glib" --size 240x135 --script "$scratch/switch.script" \
    --record "$scratch/switch.session" >"$scratch/lake.log" 2>&1
rc=$?
cat "$scratch/lake.log"
[ "$rc" -eq 0 ] || fail "tarn view exited $rc"
[ "$(grep -c 'holds the expected value' "$scratch/lake.log")" -eq 3 ] || fail "an expect is missing"
[ -s "$scratch/raymarch.png" ] && [ -s "$scratch/natural.png" ] || fail "no screenshots"
cmp -s "$scratch/raymarch.png" "$scratch/natural.png" && fail "the picture did not change with the pack"
# a recording notes each switch, after a header naming the pack it began with
grep -q "^pack raymarch$" "$scratch/switch.session" || fail "the session's header does not name the lake's pack"
[ "$(grep -c " pack natural$" "$scratch/switch.session")" -eq 1 ] || fail "the switch to natural was not recorded"
[ "$(grep -c " pack raymarch$" "$scratch/switch.session")" -eq 1 ] || fail "the switch back to raymarch was not recorded"

cat > "$scratch/glman.script" <<'SCRIPT'
frames 1
pack natural
frames 1
expect Flat uGrey 0.25
reload
frames 1
expect Flat uGrey 0.25
quit
SCRIPT
cp "$src/tests/data/window/grey.vert" "$src/tests/data/window/grey.frag" "$src/tests/data/window/scene.glib" "$scratch/"
(cd "$scratch" && xvfb "$bin" view scene.glib --script glman.script >"$scratch/glman.log" 2>&1)
rc=$?
cat "$scratch/glman.log"
# the failed switch is a failed load: a scripted run then exits 1 (input)
[ "$rc" -eq 0 ] || [ "$rc" -eq 1 ] || fail "tarn view exited $rc"
grep -q "this scene describes no world" "$scratch/glman.log" || fail "no reason for refusing the pack"
[ "$(grep -c 'Flat.uGrey holds the expected value' "$scratch/glman.log")" -eq 2 ] || fail "the glman scene was lost"
# the refused pack is not kept: a later reload (a save) loads the scene as it is
[ "$(grep -c "this scene describes no world" "$scratch/glman.log")" -eq 1 ] || fail "a reload after the refusal tried the pack again"
echo "window pack test: ok"
