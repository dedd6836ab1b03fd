#!/usr/bin/env bash
# vector_width_ab: llvmpipe's SIMD width, its default (the CPU's widest: 256
# bits on AVX2) against LP_NATIVE_VECTOR_WIDTH=128, one binary, interleaved
# in one run so both see the same machine load (docs/benchmark.md,
# "llvmpipe's vector width": 128 compiles a fifth faster and draws a third
# slower, so tarn leaves the default). Per pack, ROUNDS rounds of each
# width in turn:
#   - compile: the water pass's time in the first frame of a 64x36 render with
#     Mesa's shader cache off (its cold compile, what a save of water.frag pays;
#     scripts/compile_bench.sh's figure), and the whole process's wall time
#     (every shader of the pack compiled, the first picture);
#   - frame: `tarn render scenes/lake.glib --frames 8 --time 2 --msaa 1` at
#     960x540 (issue #25's animated frame, the window's case), wall ms;
#   - pixels: that frame of each width compared (RMSE; 0 is bit for bit).
# Each width keeps a Mesa shader cache of its own for the frames: Mesa's
# cache key does not hold the width (the jitted code's interface is a
# block of pixels at any width, so either width runs the other's code, the
# same pixels), and a shared cache would time one width's code twice.
# Prints the medians per pack and width. Timing belongs here, not in a test.
# Usage: scripts/vector_width_ab.sh [TARN] [ROUNDS] [PACK...]   (build/tarn, 3, all four)
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
tarn=${1:-$here/build/tarn}; shift || true
rounds=${1:-3}; shift || true
packs=("$@")
[ ${#packs[@]} -gt 0 ] || packs=(basic raymarch natural caustic_tex)
[ -x "$tarn" ] || { echo "vector_width_ab: no tarn at $tarn (build first)"; exit 2; }
if [ -n "${LP_NATIVE_VECTOR_WIDTH:-}" ]; then
  echo "vector_width_ab: unset LP_NATIVE_VECTOR_WIDTH first (llvmpipe's default is one of the two sides)"; exit 2
fi
scratch=$(mktemp -d /tmp/tarn-vw.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
scene=$here/scenes/lake.glib
echo "vector_width_ab: $(uptime | sed 's/^ *//'); $rounds rounds; $tarn"

median() { sort -n | awk '{ v[NR] = $1 } END { if (NR) print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }

# one measurement of width W ("128", or "" for llvmpipe's default) for pack P, round R
measure() {   # P W R
  local w=$2 tag=${2:-default} t0 t1 out
  t0=$(date +%s%N)
  out=$(env ${w:+LP_NATIVE_VECTOR_WIDTH=$w} MESA_SHADER_CACHE_DISABLE=true "$tarn" render "$scene" --pack "$1" \
        --size 64x36 --msaa 1 --frames 1 --passes --out /dev/null 2>&1)
  t1=$(date +%s%N)
  echo "$out" | awk '/WaterSurface/ && /\(1 frame\)/ { v = $2 } END { print v }' >> "$scratch/$1-$tag.water"
  echo $(( (t1 - t0) / 1000000 )) >> "$scratch/$1-$tag.process"
  env ${w:+LP_NATIVE_VECTOR_WIDTH=$w} MESA_SHADER_CACHE_DIR="$scratch/cache-$tag" \
      "$tarn" render "$scene" --pack "$1" --frames 8 --time 2 --msaa 1 \
      -o "$scratch/$1-$tag.png" 2>&1 | sed -n 's/.* wall \([0-9.]*\) ms.*/\1/p' >> "$scratch/$1-$tag.frame"
}

printf "| pack | width | water pass cold compile, ms | process, cold, ms | animated frame 960x540, ms | pixels |\n"
printf "|---|---|---:|---:|---:|---|\n"
for p in "${packs[@]}"; do
  for r in $(seq "$rounds"); do measure "$p" "" "$r"; measure "$p" 128 "$r"; done
  rmse=$("$tarn" compare "$scratch/$p-128.png" "$scratch/$p-default.png" --csv - 2>/dev/null |
         awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next } { print $c["rmse"] }')
  for tag in default 128; do
    printf "| %s | %s | %s | %s | %s | %s |\n" "$p" "$tag" "$(median < "$scratch/$p-$tag.water")" \
      "$(median < "$scratch/$p-$tag.process")" "$(median < "$scratch/$p-$tag.frame")" \
      "$([ "$tag" = 128 ] && echo "RMSE $rmse against the default" || echo "")"
  done
done
