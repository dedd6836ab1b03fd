#!/usr/bin/env bash
# window_bench: the view window's frame budget, measured (issue #15). For
# each pack, `tarn view` on the lake (its WindowSize, 960x540 beside the
# panel) under Xvfb, driven by a --script:
#   - orbiting: the camera turns every frame; after 20 frames for the
#     budget to settle, the wall time of the next 40 frames gives the fps,
#     and the internal resolution they ended at;
#   - animating (issue #30 item 3): the camera still and the clock
#     running (the script's `play 1`), after 20 frames to settle, the next
#     40: fps and the internal resolution they ended at (what a person
#     editing against the moving water sees); then the same with the
#     world's caches off (`world-cache 0`: the static world and its layers
#     drawn whole every frame, as before they were kept);
#   - save -> first new frame: the picture still (paused, the full frame
#     drawn and kept), the pack's water shader is saved (a line appended, in
#     a scratch copy of packs/ and scenes/ under TARN_ROOT), a different
#     line every run (its time in ns), so Mesa's shader cache never answers
#     for the edited stage (issue #30: the same comment every run measured
#     the cache, not the compiler); the wall clock of the save against the
#     swap of the first frame after the reload (the script's `stamp on`),
#     and from the reload's start (loading and compiling, then the frame).
#     Three times: "cold", Mesa's shader cache off (MESA_SHADER_CACHE_DISABLE:
#     every stage the reload links compiles, as on a first run; with no
#     cache the window compiles on the frame), "warm", the cache holding
#     every stage but the edited one (a first, unmeasured run of the same
#     scene fills it): what a user editing one file meets, the change
#     compiled off the frame (viewer/ui/compile_job.h), and "warm/frame",
#     the same compiled on the frame (TARN_COMPILE_ON_FRAME=1, as before
#     issue #30) for the A/B. "longest gap" is the longest time between two
#     frames on screen from the save's detection to the new frame: how long
#     the window froze.
# Usage: scripts/window_bench.sh [TARN] [BUDGET_MS[,BUDGET_MS...]] [PACK...]
#   TARN defaults to build/tarn, BUDGET_MS to 50 (0: the budget off; "0,50"
#   runs both, one after the other for each pack: an A/B in one run).
# Timing on a shared machine is noisy: say whether it was idle (uptime).
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build/tarn}; shift || true
budget=${1:-50}; shift || true
packs=("$@")
[ ${#packs[@]} -gt 0 ] || packs=(basic raymarch natural caustic_tex)
command -v xvfb-run >/dev/null || { echo "window_bench: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
scratch=$(mktemp -d /tmp/tarn-window-bench.XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$scratch"' EXIT
cp -r "$here/packs" "$here/scenes" "$scratch/"
[ -d "$here/data" ] && cp -r "$here/data" "$scratch/"
echo "window_bench: $(uptime | sed 's/^ *//')"
echo "window_bench: lake at its WindowSize, $bin"
printf "%-12s %10s %7s %10s %14s %18s %9s %18s %15s %12s %14s %12s\n" pack cache budget "orbit fps" "orbit ms/frame" "orbit resolution" \
    "anim fps" "anim resolution" "no-cache fps,res" \
    "save->frame" "reload->frame" "longest gap"
for p in "${packs[@]}"; do
  for cache in cold warm warm/frame; do
  export MESA_SHADER_CACHE_DIR=$scratch/mesa-$p-${cache%/*}
  rm -rf "$MESA_SHADER_CACHE_DIR" && mkdir -p "$MESA_SHADER_CACHE_DIR"
  if [ $cache = cold ]; then export MESA_SHADER_CACHE_DISABLE=true; else unset MESA_SHADER_CACHE_DISABLE; fi
  if [ $cache = warm/frame ]; then export TARN_COMPILE_ON_FRAME=1; else unset TARN_COMPILE_ON_FRAME; fi
  if [ $cache != cold ]; then   # fill the cache with this scene's stages, unmeasured
    printf 'pause 1\nframes 3\nquit\n' > "$scratch/fill.script"
    TARN_ROOT=$scratch xvfb-run -a -s "-screen 0 1600x900x24" "$bin" view "$scratch/scenes/lake.glib" --pack "$p" \
        --time 2 --script "$scratch/fill.script" > /dev/null 2>&1
  fi
  for b in ${budget//,/ }; do
    frag=$(awk '$1 == "Fragment" { f = $2 } END { print f }' "$scratch/packs/$p/pack.glib")
    cat > "$scratch/bench.script" <<SCRIPT
pause 1
budget $b
frames 3
orbit 0.01 0 1000
frames 20
clock
frames 40
clock
resolution
orbit 0 0 1
pause 0
play 1
frames 20
clock
frames 40
clock
resolution
world-cache 0
frames 20
clock
frames 40
clock
resolution
world-cache 1
pause 1
play 0
time 2
wait 2
stamp on
wait 8
quit
SCRIPT
    log=$scratch/$p-${cache/\//-}-$b.log
    TARN_ROOT=$scratch xvfb-run -a -s "-screen 0 1600x900x24" "$bin" view "$scratch/scenes/lake.glib" --pack "$p" \
        --time 2 --script "$scratch/bench.script" > "$log" 2>&1 &
    pid=$!
    # the save: once the script is stamping, with the full frame kept
    while kill -0 $pid 2>/dev/null && ! grep -q "stamp on" "$log" 2>/dev/null; do sleep 0.1; done
    sleep 1
    saved=$(date +%s.%N)
    echo "// saved by window_bench ($b, $cache, $(date +%s%N))" >> "$scratch/packs/$p/$frag"
    wait $pid
    rc=$?
    read -r f0 c0 f1 c1 f2 c2 f3 c3 f4 c4 f5 c5 < <(awk '/clock/ { printf "%s %s ", $3, $5 } END { print "" }' "$log")
    nres=$(awk '/resolution/ { print $3 }' "$log" | sed -n 3p)
    nfps=$(awk -v f0="$f4" -v f1="$f5" -v c0="$c4" -v c1="$c5" 'BEGIN { if (c1 > c0) printf "%.1f", (f1 - f0) * 1000 / (c1 - c0); else print "-" }')
    res=$(awk '/resolution/ { print $3 }' "$log" | head -1)
    ares=$(awk '/resolution/ { print $3 }' "$log" | sed -n 2p)
    afps=$(awk -v f0="$f2" -v f1="$f3" -v c0="$c2" -v c1="$c3" 'BEGIN { if (c1 > c0) printf "%.1f", (f1 - f0) * 1000 / (c1 - c0); else print "-" }')
    swap=$(awk '/first frame after the reload swapped at/ { print $10; exit }' "$log")
    fps=$(awk -v f0="$f0" -v f1="$f1" -v c0="$c0" -v c1="$c1" 'BEGIN { if (c1 > c0) printf "%.1f", (f1 - f0) * 1000 / (c1 - c0); else print "-" }')
    ms=$(awk -v f0="$f0" -v f1="$f1" -v c0="$c0" -v c1="$c1" 'BEGIN { if (f1 > f0) printf "%.1f", (c1 - c0) / (f1 - f0); else print "-" }')
    rl=$(awk '/first frame after the reload swapped at/ { sub(/^\(/, "", $11); print $11 " ms"; exit }' "$log")
    gap=$(awk '/first frame after the reload swapped at/ { for (i = 1; i < NF; i++) if ($i == "gap") print $(i + 2) " ms"; exit }' "$log")
    lat=$(awk -v s="$saved" -v w="$swap" 'BEGIN { if (w != "") printf "%.0f ms", (w - s) * 1000; else print "-" }')
    printf "%-12s %10s %7s %10s %14s %18s %9s %18s %15s %12s %14s %12s%s\n" "$p" "$cache" "$b" "$fps" "$ms" "$res" "$afps" "${ares:--}" \
        "$nfps,${nres:--}" \
        "$lat" "${rl:--}" "${gap:--}" \
        "$([ "$rc" -eq 0 ] || echo "  (tarn exited $rc)")"
  done
  done
done
