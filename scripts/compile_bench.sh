#!/usr/bin/env bash
# compile_bench: what each pack's first frame costs to compile, cold. On a
# CPU rasteriser (llvmpipe) a pass's time in the first frame of a tiny
# render with Mesa's shader cache off is its shaders' compile, and a save
# of a pack's water shader pays that pass's figure again (issue #30 item 2).
# A shader edit that sends LLVM down a slow path shows here as one pass
# taking seconds (natural's water: 0.35 -> 5.5 s from one textureLod in a
# loop, unseen until a save took 22 s; docs/benchmark.md, "natural's
# compile"). Run it after a change to a pack's shaders.
# Usage: scripts/compile_bench.sh [TARN] [SCENE]  (defaults: build/tarn, scenes/lake.glib)
#   Prints, per pack, the first frame's wall time and its three costliest
#   passes. One run; cold compiles vary by up to half from run to run.
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
tarn=${1:-$here/build/tarn}
scene=${2:-$here/scenes/lake.glib}
[ -x "$tarn" ] || { echo "compile_bench: no tarn at $tarn (build first)"; exit 2; }
echo "compile_bench: $(uptime | sed 's/^ *//')"
echo "| pack | first frame, s | costliest passes (cold compile + draw at 64x36), ms |"
echo "|---|---:|---|"
for pack in basic raymarch natural caustic_tex; do
  out=$(MESA_SHADER_CACHE_DISABLE=true "$tarn" render "$scene" --pack "$pack" --size 64x36 --msaa 1 \
        --frames 1 --passes --out /dev/null 2>&1)
  wall=$(echo "$out" | sed -n 's/.*wall \([0-9.]*\) ms.*/\1/p' | head -1)
  top=$(echo "$out" | awk '/ ms +\(1 frame\)/ { ms = $(NF - 3); $NF = ""; $(NF - 1) = ""; $(NF - 2) = ""; $(NF - 3) = "";
                         sub(/ +$/, ""); sub(/^ +/, ""); printf "%.0f\t%s\n", ms, $0 }' |
        sort -rn | head -3 | awk -F'\t' '{ printf "%s%s %s", (NR > 1 ? ", " : ""), $2, $1 }')
  printf '| %s | %s | %s |\n' "$pack" "$(awk -v w="${wall:-0}" 'BEGIN { printf "%.2f", w / 1000 }')" "$top"
done
