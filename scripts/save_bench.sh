#!/usr/bin/env bash
# save_bench: save -> first new frame in a window, several saves a window,
# two or more builds alternating (issue #30 item 2: an A/B on one machine
# in one run). For each round and each TARN given, `tarn view` on the lake
# with PACK under Xvfb at t = 2 s with the 50 ms budget, paused (a still
# picture, its full frame drawn and kept) or with --running the clock
# running (animated frames drawn meanwhile), in a
# scratch copy of packs/ and scenes/ (TARN_ROOT) whose Mesa shader cache is
# first filled by an unmeasured run ("warm": every stage but the edited one
# cached). Then SAVES saves of the pack's water shader, 5 s apart, each a
# new line (its time in ns), so Mesa's cache never answers for the edited
# stage. Each save's figure is the wall clock from the save to the swap of
# the first frame after its reload (the script's `stamp on`), then the
# longest frame gap until that frame and in the second after it (issue
# #30: none longer than the budget while a save compiles), and, paused,
# the save to the first full-resolution frame (the first new frame is a
# reduced one: the change seen sharp); the last lines give each build's
# medians over all its saves.
# Usage: scripts/save_bench.sh [--saves N] [--rounds R] [--running] PACK TARN [TARN...]
#   (defaults: 6 saves, 3 rounds; --running: the clock runs, as a user's
#   usually does, and the window draws animated frames meanwhile). A shared machine is noisy: say whether
#   it was idle (uptime), and compare medians of the same run only.
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
saves=6 rounds=3 clock='pause 1'
while [ $# -gt 0 ]; do
  case $1 in
    --saves) saves=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --running) clock='play 1'; shift ;;
    *) break ;;
  esac
done
[ $# -ge 2 ] || { echo "usage: scripts/save_bench.sh [--saves N] [--rounds R] [--running] PACK TARN [TARN...]"; exit 2; }
pack=$1; shift
command -v xvfb-run >/dev/null || { echo "save_bench: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
scratch=$(mktemp -d /tmp/tarn-save-bench.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
echo "save_bench: $(uptime | sed 's/^ *//')"
echo "save_bench: $pack on the lake, $saves saves a window, $rounds rounds, warm Mesa cache, clock: $clock"

# one window of one build: prints each save's ms
one_window() {
  local bin=$1 dir=$scratch/run
  rm -rf "$dir" && mkdir -p "$dir"
  cp -r "$here/packs" "$here/scenes" "$dir/"
  [ -d "$here/data" ] && cp -r "$here/data" "$dir/"
  export MESA_SHADER_CACHE_DIR=$dir/mesa
  local frag
  frag=$(awk '$1 == "Fragment" { f = $2 } END { print f }' "$dir/packs/$pack/pack.glib")
  printf 'pause 1\nframes 3\nquit\n' > "$dir/fill.script"
  TARN_ROOT=$dir xvfb-run -a -s "-screen 0 1600x900x24" "$bin" view "$dir/scenes/lake.glib" --pack "$pack" \
      --time 2 --script "$dir/fill.script" > /dev/null 2>&1
  { printf '%s\nbudget 50\ntime 2\nwait 2\nstamp on\n' "$clock"
    for _ in $(seq "$saves"); do printf 'wait 5\n'; done
    printf 'quit\n'; } > "$dir/bench.script"
  TARN_ROOT=$dir xvfb-run -a -s "-screen 0 1600x900x24" "$bin" view "$dir/scenes/lake.glib" --pack "$pack" \
      --time 2 --script "$dir/bench.script" > "$dir/log" 2>&1 &
  local pid=$!
  while kill -0 $pid 2>/dev/null && ! grep -q "stamp on" "$dir/log"; do sleep 0.1; done
  sleep 1.5
  for _ in $(seq "$saves"); do
    date +%s.%N >> "$dir/saved"
    echo "// saved by save_bench $(date +%s%N)" >> "$dir/packs/$pack/$frag"
    sleep 5
  done
  wait $pid
  paste "$dir/saved" <(awk '/first frame after the reload swapped at/ { print $10 }' "$dir/log") |
      awk 'NF == 2 { printf "%.0f ", ($2 - $1) * 1000 } NF != 2 { printf "- " }'
  # the longest frame gap until each save's first new frame (that frame's
  # own: the reload), then in the second after it (the job's still frame)
  printf '| '
  sed -n 's/.*longest frame gap meanwhile \([0-9.]*\) ms.*/\1/p' "$dir/log" | awk '{ printf "%.0f ", $1 }'
  printf '| '
  sed -n 's/.*in the [0-9.]* s after that frame, longest frame gap \([0-9.]*\) ms.*/\1/p' "$dir/log" |
      awk '{ printf "%.0f ", $1 }'
  # paused: each save's first full-resolution frame (the first new one
  # may be reduced: the change seen sharp)
  printf '| '
  paste "$dir/saved" <(awk '/full frame after the reload swapped at/ { print $10 }' "$dir/log") |
      awk 'NF == 2 { printf "%.0f ", ($2 - $1) * 1000 }'
}

median() {
  tr ' ' '\n' | grep -v '^-*$' | sort -n |
      awk '{ v[NR] = $1 } END { if (NR) print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) " ms over " NR; else print "-" }'
}

declare -A all to after full
for r in $(seq "$rounds"); do
  for bin in "$@"; do
    bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
    out=$(one_window "$bin")
    echo "round $r  $bin: $out"
    IFS='|' read -r ms gap_to gap_after sharp <<< "$out"
    all[$bin]="${all[$bin]:-} $ms"
    to[$bin]="${to[$bin]:-} $gap_to"
    after[$bin]="${after[$bin]:-} $gap_after"
    full[$bin]="${full[$bin]:-} $sharp"
  done
done
for bin in "$@"; do
  bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
  echo "median $bin: $(echo ${all[$bin]} | median) saves; longest frame gap to the new frame $(echo ${to[$bin]} | median), in the second after it $(echo ${after[$bin]} | median)"
  [ -n "$(echo ${full[$bin]:-})" ] && echo "median $bin: save -> the first full-resolution frame (paused) $(echo ${full[$bin]} | median) saves"
done
