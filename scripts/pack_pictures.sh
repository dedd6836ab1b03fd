#!/usr/bin/env bash
# Regenerates the pictures of the pack pages (docs/packs/img/) and prints
# the water error the pages quote, from one tarn build:
#
#   lake_reference.png          `tarn reference scenes/lake.glib`, 480x270, t = 1
#   PACK_paper.png, PACK_default.png   the lake drawn by PACK with its bench.txt
#                               setting (`tarn render --setting`), the same
#                               camera (the scene's), size and time
#   the headline stills         each pack's own effect, its own camera (below)
#
# and, per pack and setting, the water RMSE against the reference at
# t = 1 and t = 4 (the times of docs/benchmark.md, 480x270, default
# reference quality) and their mean, which is what the benchmark's table
# reports. References and renders go to out/pictures (kept: a rerun
# renders no reference twice). Takes about 10 minutes on 2 cores.
#
#   scripts/pack_pictures.sh [TARN]       (default build/tarn)
set -euo pipefail
cd "$(dirname "$0")/.."
tarn=${1:-build/tarn}
img=docs/packs/img
work=out/pictures
size=480x270
lake=$PWD/scenes/lake.glib
mkdir -p "$work" "$img"

# the lake seen from another camera: NAME LOOKAT...
view_of_lake() {
    local name=$1; shift
    printf '##OpenGL GLIB\n# scripts/pack_pictures.sh: the lake from another camera\nInclude "%s"\nLookAt %s\n' \
        "$lake" "$*" > "$work/$name.glib"
    echo "$work/$name.glib"
}

water_rmse() {   # A.exr REF.exr: the water RMSE (tarn compare's water_rmse), unrounded
    "$tarn" compare "$1" "$2" --json - 2>/dev/null |
        python3 -c 'import json,sys; print(json.load(sys.stdin)["water_rmse"])'
}

for t in 1 4; do
    [ -s "$work/ref_t$t.exr" ] || "$tarn" reference "$lake" --size $size --time $t -o "$work/ref_t$t.exr" --quiet
done
cp "$work/ref_t1.png" "$img/lake_reference.png"

printf '%-12s %-8s %10s %10s %10s\n' pack setting "t=1" "t=4" mean
for pack in natural raymarch caustic_tex basic; do
    for setting in default paper; do
        [ "$pack" = basic ] && [ "$setting" = paper ] && continue   # basic has no paper: it is tarn's baseline
        e=()
        for t in 1 4; do
            "$tarn" render "$lake" --pack $pack --setting $setting --size $size --time $t --quiet \
                -o "$work/${pack}_${setting}_t$t.exr"
            e+=("$(water_rmse "$work/${pack}_${setting}_t$t.exr" "$work/ref_t$t.exr")")
        done
        [ "$pack" = basic ] || "$tarn" render "$lake" --pack $pack --setting $setting --size $size --time 1 \
            --quiet -o "$img/${pack}_${setting}.png"
        printf '%-12s %-8s %10.4f %10.4f %10.4f\n' $pack $setting "${e[0]}" "${e[1]}" \
            "$(python3 -c "print((${e[0]} + ${e[1]}) / 2)")"
    done
done

# the headline effects, default settings, t = 1
# natural's caustics on the floor seen through clear water, from caustic_tex's headline camera
"$tarn" render "$(view_of_lake headline 3 2.2 3  0.5 -1.2 -0.5  0 1 0)" --pack natural --size $size --time 1 \
    --quiet -o "$img/natural_caustics.png"
# natural's glint against the paper's lobe, looking down into the sun's reflection
for setting in paper default; do
    "$tarn" render "$(view_of_lake glint -3 5 3  1.5 -0.6 -1.5  0 1 0)" --pack natural --setting $setting \
        --size $size --time 1 --quiet -o "$img/natural_glint_$setting.png"
done
"$tarn" render "$(view_of_lake reflections 8 1.0 3  2 0.0 -3  0 1 0)" --pack raymarch --size $size --time 1 \
    --quiet -o "$img/raymarch_reflections.png"
"$tarn" render "$(view_of_lake headline 3 2.2 3  0.5 -1.2 -0.5  0 1 0)" --pack caustic_tex --size $size --time 1 \
    --quiet -o "$img/caustic_tex_headline.png"
"$tarn" render "$PWD/scenes/hard/underwater.glib" --pack caustic_tex --size $size --time 1 --quiet \
    -o "$img/caustic_tex_below.png"
echo "wrote $img"
