#!/usr/bin/env bash
# live_error: how close the window's picture is to the full-resolution
# frame while the water moves (issue #25 item 4). For each pack, `tarn view`
# on the lake (960x540 beside the panel) under Xvfb, the clock running and
# the camera still at the default 50 ms budget, driven by a --script, in
# two modes taken in turn at each of GRABS instants:
#   - "sharp world" (the window's default): the reduced frame's water over
#     the world kept at full resolution (gfx/upscale.h);
#   - "enlarged": `sharp-world 0`, the whole reduced frame enlarged by the
#     bilinear blit, the window before.
# The script drives the clock (`advance`, 50 ms of scene time a frame, as a
# clock running at the budget's 20 fps), so both modes grab the very same
# instants: the water's error changes more from one instant to another than
# between the modes. For each instant and mode: 20 frames of animation
# leading to it, every one drawn (the budget settles on the mode; their fps
# is the mode's frame rate), then the frame at the instant grabbed as the window showed
# it (the script's `grab`: the scene area, not redrawn), with the size
# drawn. Each grab is measured against `tarn render` of the same instant at
# 960x540 without MSAA (what the paused window draws) by `tarn compare`:
# RMSE (linear RGB), FLIP (mean) and SSIM; the table gives each mode's mean
# over the instants, its mean fps and the range of sizes drawn.
# Usage: scripts/live_error.sh [TARN] [PACK...]   (GRABS=6, SCENE=scenes/lake.glib
# by default; a scene other than the lake must have a WindowSize of 960x540)
# Timing on a shared machine is noisy: say whether it was idle (uptime).
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build/tarn}; shift || true
packs=("$@")
[ ${#packs[@]} -gt 0 ] || packs=(basic raymarch natural caustic_tex)
grabs=${GRABS:-6}
command -v xvfb-run >/dev/null || { echo "live_error: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
scene=${SCENE:-$here/scenes/lake.glib}
scratch=$(mktemp -d /tmp/tarn-live-error.XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$scratch"' EXIT
echo "live_error: $(uptime | sed 's/^ *//')"
echo "live_error: $(basename "$scene") at 960x540, budget 50 ms, $grabs grabs a mode, $bin"

# one turn of a mode: 20 frames of animation up to instant T, each a new
# picture 50 ms of scene time after the one before (`advance`; the fps
# over them), then the frame at T, grabbed. (Before 2026-12-07 the turn
# set each instant by `time` and `frames 1`, which then let two frames
# pass: a drawn one and a kept one, so the fps column counted twice the
# pictures drawn.)
turn() {   # MODE(1 sharp, 0 enlarged) T GRAB-PATH
  echo "sharp-world $1"
  echo "time $(awk -v t="$2" 'BEGIN { printf "%.3f", t - 0.05 * 21 }')"
  echo "clock"
  echo "advance 0.05 20"
  echo "clock"
  echo "advance 0.05 1"
  echo "grab $3"
}

# RMSE FLIP SSIM of a grab against the render of its time
measure() {   # PACK PNG TIME
  "$bin" render "$scene" --pack "$1" --time "$3" --msaa 1 --size 960x540 -o "$scratch/truth.png" --quiet || return 1
  "$bin" compare "$2" "$scratch/truth.png" --csv - 2>/dev/null | awk -F, '
    NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    { print $col["rmse"], $col["flip_mean"], $col["ssim"] }'
}

printf "%-12s %-9s %6s %-19s %8s %8s %8s\n" pack mode fps "drawn at" RMSE FLIP SSIM
for p in "${packs[@]}"; do
  {
    # (5 s: the start's "F1 or ? shows the keys" toast, 4 s, gone before
    # the first grab; a fast window reached it under the toast)
    printf 'pause 1\nbudget 50\nframes 3\npause 0\nplay 1\nwait 5\nplay 0\n'
    for g in $(seq 1 "$grabs"); do
      t=$(awk -v g="$g" 'BEGIN { printf "%.3f", 3 + 1.7 * g }')
      turn 1 "$t" "$scratch/$p-sharp-$g.png"; turn 0 "$t" "$scratch/$p-enlarged-$g.png"
    done
    echo quit
  } > "$scratch/$p.script"
  log=$scratch/$p.log
  xvfb-run -a -s "-screen 0 1600x900x24" "$bin" view "$scene" --pack "$p" --time 2 \
      --script "$scratch/$p.script" > "$log" 2>&1 || { echo "$p: tarn view failed:"; tail -5 "$log"; continue; }
  # fps of each turn: its two clock lines (turns alternate sharp, enlarged)
  awk '/ clock / { c++; f[c] = $3; ms[c] = $5 }
       END { for (k = 1; 2 * k <= c; k++) print (k % 2 ? "sharp" : "enlarged"), (f[2*k] - f[2*k-1]) * 1000 / (ms[2*k] - ms[2*k-1]) }' \
      "$log" > "$scratch/$p.fps"
  sed -n "s|^tarn: grab \($scratch/$p-\([a-z]*\)-[0-9]*\.png\) at t=\([^,]*\), drawn at \([0-9x]*\) of.*|\2 \1 \3 \4|p" "$log" |
    while read -r mode png t size; do echo "$mode $size $(measure "$p" "$png" "$t")"; done > "$scratch/$p.err"
  for mode in sharp enlarged; do
    fps=$(awk -v m=$mode '$1 == m { s += $2; n++ } END { if (n) printf "%.1f", s / n }' "$scratch/$p.fps")
    awk -v m=$mode -v p="$p" -v fps="$fps" '$1 == m && NF == 5 {
        split($2, wh, "x"); a = wh[1] * wh[2]
        if (!n || a < amin) { amin = a; smin = $2 } if (!n || a > amax) { amax = a; smax = $2 }
        r += $3; f += $4; s += $5; n++ }
      END { if (n) printf "%-12s %-9s %6s %-19s %8.4f %8.4f %8.4f\n", p, m, fps, smin "-" smax, r / n, f / n, s / n }' \
      "$scratch/$p.err"
  done
done
