#!/usr/bin/env bash
# Before/after speed of two tarn builds in ONE run, interleaved, so both see
# the same machine load: for each pack, ROUNDS rounds of "before renders
# FRAMES frames, after renders FRAMES frames" on the same scene, size and
# simulated time; the wall ms per frame that `tarn render --frames` prints
# are pooled per build and the medians compared. Also the water-only error
# of each build's frame against the CPU reference (tarn compare), so a
# speed-up that costs accuracy shows.
#
#   scripts/speed_ab.sh BEFORE_TARN AFTER_TARN [options]
#     --scene F      default scenes/lake.glib
#     --size WxH     timing size (default 960x540)
#     --err-size WxH error size (default 480x270; the reference is cached)
#     --time T       simulated time (default 2)
#     --packs a,b    default: basic,raymarch,natural,caustic_tex
#     --rounds N     default 3;  --frames N  default 6 (the median is
#                    taken over all, so the first two, which fill caches, are outliers)
#     --msaa N       anti-aliasing of the timed frames and of the error's
#                    (default: tarn render's, 4 samples; 1 is the live
#                    window's case on a CPU rasteriser), the reference sampled
#                    to match
#     --still        every frame at the same time (tarn render --still: what a
#                    paused window and tarn bench draw, so the static-world
#                    cache is used); a build without --still, which has no
#                    cache either, renders its frames 1/60 s apart as before
#     BEFORE_ROOT / AFTER_ROOT (env): the trees whose scene and packs each
#     build draws (default: the folder above the binary's build folder,
#     e.g. /old/checkout for /old/checkout/build/tarn)
#
# Prints a Markdown table: pack, before ms, after ms, ratio, water RMSE
# before/after. Timing belongs here, never in a pass/fail test.
set -euo pipefail
[ $# -ge 2 ] || { sed -n 2,19p "$0"; exit 2; }
before=$1 after=$2; shift 2
scene=scenes/lake.glib size=960x540 esize=480x270 t=2 rounds=3 frames=6 still=0 msaa=
packs=basic,raymarch,natural,caustic_tex
while [ $# -gt 0 ]; do
    case $1 in
    --scene) scene=$2; shift ;;
    --size) size=$2; shift ;;
    --err-size) esize=$2; shift ;;
    --time) t=$2; shift ;;
    --packs) packs=$2; shift ;;
    --rounds) rounds=$2; shift ;;
    --frames) frames=$2; shift ;;
    --still) still=1 ;;
    --msaa) msaa=$2; shift ;;
    *) echo "speed_ab.sh: unknown option $1" >&2; exit 2 ;;
    esac
    shift
done
root_of() { (cd "$(dirname "$1")/.." && pwd); }
broot=${BEFORE_ROOT:-$(root_of "$before")} aroot=${AFTER_ROOT:-$(root_of "$after")}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# one build's wall ms per frame for one pack (the median tarn render prints)
wall() {  # tarn root pack
    local out opt=()
    if [ "$still" = 1 ] && [[ $("$1" render --help 2>&1) == *--still* ]]; then opt=(--still); fi
    if [ -n "$msaa" ]; then opt+=(--msaa "$msaa"); fi
    out=$(TARN_ROOT=$2 "$1" render "$2/$scene" --pack "$3" --size "$size" --time "$t" \
          --frames "$frames" "${opt[@]}" -o "$tmp/f.png" 2>&1) || { echo "$out" >&2; return 1; }
    sed -n 's/.* wall \([0-9.]*\) ms.*/\1/p' <<<"$out"
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
water_rmse() {  # tarn root pack (at the timed frames' --msaa, against a reference sampled to match)
    local opt=()
    if [ -n "$msaa" ]; then opt=(--msaa "$msaa"); fi
    TARN_ROOT=$2 "$1" render "$2/$scene" --pack "$3" --size "$esize" --time "$t" "${opt[@]}" -o "$tmp/e.exr" --quiet 2>/dev/null
    "$1" compare "$tmp/e.exr" "$tmp/ref.exr" 2>&1 | awk "/^water RMSE/ {print \$NF}" | head -1
}

ref_opt=()
if [ -n "$msaa" ]; then ref_opt=(--msaa "$msaa"); fi
"$after" reference "$aroot/$scene" --time "$t" --size "$esize" "${ref_opt[@]}" -o "$tmp/ref.exr" >/dev/null
echo "before: $before on $broot; after: $after on $aroot"
echo "scene $scene, timing at $size, t = $t s, $rounds rounds x $frames frames per build, interleaved;"
[ "$still" = 1 ] && echo "still frames (--still where the build has it)"
echo "water RMSE at $esize${msaa:+ and --msaa $msaa} against the CPU reference"
echo
echo "| pack | before ms | after ms | speed-up | water RMSE before | after |"
echo "|---|---:|---:|---:|---:|---:|"
IFS=, read -ra list <<<"$packs"
for p in "${list[@]}"; do
    : >"$tmp/b" ; : >"$tmp/a"
    for ((i = 0; i < rounds; i++)); do
        wall "$before" "$broot" "$p" >>"$tmp/b"
        wall "$after" "$aroot" "$p" >>"$tmp/a"
    done
    mb=$(median <"$tmp/b") ma=$(median <"$tmp/a")
    eb=$(water_rmse "$before" "$broot" "$p") ea=$(water_rmse "$after" "$aroot" "$p")
    printf '| %s | %.0f | %.0f | %.2fx | %s | %s |\n' "$p" "$mb" "$ma" "$(echo "$mb / $ma" | bc -l)" "$eb" "$ea"
done
