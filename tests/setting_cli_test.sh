#!/usr/bin/env bash
# `tarn render --setting NAME` draws what the row's assignments give as
# `--set`s (packs/natural/bench.txt's paper and mesh-64, the latter a
# scene.WaterMesh); a name the pack lacks is an input error naming the
# ones it has; a session's `setting paper` replays (`tarn record`) as the
# same assignments written as define events do.
set -u
bin=$1; src=$2
fail() { echo "FAIL: $*"; exit 1; }
scratch=$PWD/setting-cli-test
rm -rf "$scratch" && mkdir -p "$scratch" || fail "no scratch directory"
lake=$src/scenes/lake.glib
render() { "$bin" render "$lake" --pack natural --size 160x90 --time 1 --quiet "$@"; }

render -o "$scratch/default.png"
rc=$?
[ "$rc" -eq 3 ] && { echo "skip: no OpenGL"; exit 77; }
[ "$rc" -eq 0 ] || fail "the default render exited $rc"
render --setting paper -o "$scratch/paper.png" || fail "--setting paper failed"
render --set NaturalWater.CAUSTICS_GPU=0 --set NaturalWater.EXACT_FRESNEL=0 --set NaturalWater.BEER_LAMBERT=0 \
    --set NaturalWater.REFINE_STEPS=0 --set NaturalWater.uPhotonGrid=512 --set NaturalWater.uCausticRes=256 \
    --set NaturalWater.SPECULAR=0 --set NaturalWater.OCEAN_FOAM=0 \
    -o "$scratch/paper_sets.png" || fail "the paper --sets failed"
cmp -s "$scratch/paper.png" "$scratch/paper_sets.png" || fail "--setting paper differs from its --sets"
cmp -s "$scratch/paper.png" "$scratch/default.png" && fail "--setting paper draws the default"
render --setting mesh-64 -o "$scratch/mesh.png" || fail "--setting mesh-64 failed"
render --set scene.WaterMesh=64 -o "$scratch/mesh_set.png" || fail "--set scene.WaterMesh=64 failed"
cmp -s "$scratch/mesh.png" "$scratch/mesh_set.png" || fail "--setting mesh-64 differs from its --set"
cmp -s "$scratch/mesh.png" "$scratch/default.png" && fail "--setting mesh-64 draws the default grid"
render --setting default -o "$scratch/default2.png" || fail "--setting default failed"
cmp -s "$scratch/default2.png" "$scratch/default.png" || fail "--setting default is not the default"

render --setting nope -o "$scratch/nope.png" 2>"$scratch/nope.log"
rc=$?
cat "$scratch/nope.log"
[ "$rc" -eq 1 ] || fail "--setting nope exited $rc, not 1"
grep -q "the natural pack has no such setting; it has default paper" "$scratch/nope.log" || fail "no list of the settings"
render --set scene.Sun=1,2,3 -o "$scratch/sun.png" 2>"$scratch/sun.log"
[ $? -eq 1 ] && grep -q "scene.Sun does not apply to a running scene" "$scratch/sun.log" || fail "scene.Sun was not refused"

header="tarn-session 1
scene $lake
pack natural
size 96 54
time 1
t=0 pause 1"
printf '%s\nt=0.1 setting paper\nt=0.3 end\n' "$header" > "$scratch/setting.session"
printf '%s\nt=0.1 define NaturalWater CAUSTICS_GPU 0\nt=0.1 define NaturalWater EXACT_FRESNEL 0\nt=0.1 define NaturalWater BEER_LAMBERT 0\nt=0.1 define NaturalWater REFINE_STEPS 0\nt=0.1 slider NaturalWater uPhotonGrid 512\nt=0.1 slider NaturalWater uCausticRes 256\nt=0.1 define NaturalWater SPECULAR_FRESNEL 0\nt=0.1 slider NaturalWater uSpecular 0.5\nt=0.1 slider NaturalWater uShininess 400\nt=0.3 end\n' \
    "$header" > "$scratch/defines.session"
printf '%s\nt=0.3 end\n' "$header" > "$scratch/none.session"
for s in setting defines none; do
    "$bin" record "$scratch/$s.session" -o "$scratch/$s/" --fps 10 --quiet || fail "tarn record $s failed"
done
last() { ls "$scratch/$1"/*.png | tail -1; }
cmp -s "$(last setting)" "$(last defines)" || fail "the replayed setting differs from its define events"
cmp -s "$(last setting)" "$(last none)" && fail "the replayed setting changed nothing"
echo "setting cli test: ok"
