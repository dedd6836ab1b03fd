#!/usr/bin/env bash
# first_frame_bench: how soon a window shows its first picture (issue #30
# items 6-7). For each TARN binary given (an A/B in one run: pass the old
# build first), `tarn view` on the lake with each pack and `tarn
# compare-view` on the lake with two and four packs, under Xvfb, each run
# RUNS times; the figure is the script's first action, `clock`, which runs
# once the first frame is drawn: seconds from the process's start (GLFW's
# clock, started before the window) to the first picture on screen. Mesa's
# shader cache as it is (warm after a first run), or cold with
# MESA_SHADER_CACHE_DISABLE=true in the environment.
# compare-view draws its first pack before the others are loaded and holds
# the script until they are: its rows give the first picture (the log's
# "first picture at", GLFW's clock too) and, after a slash, the `clock`:
# every pack drawn (a build without that line: the clock alone).
# Usage: scripts/first_frame_bench.sh [RUNS] TARN...
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-2}; shift || true
bins=("$@")
[ ${#bins[@]} -gt 0 ] || bins=("$here/build/tarn")
command -v xvfb-run >/dev/null || { echo "first_frame_bench: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
script=$(mktemp /tmp/tarn-first-frame.XXXXXX)
trap 'rm -f "$script"' EXIT
printf 'clock\nquit\n' > "$script"
echo "first_frame_bench: $(uptime | sed 's/^ *//'), Mesa's shader cache $([ -n "${MESA_SHADER_CACHE_DISABLE:-}" ] && echo off || echo "as it is")"
first() {   # "FIRST/CLOCK" (or "CLOCK" alone) in seconds
  xvfb-run -a -s "-screen 0 1600x900x24" "$@" --script "$script" 2>&1 |
    awk '/ first picture at / { for (i = 1; i < NF; i++) if ($(i + 1) == "ms,") f = sprintf("%.2f/", $i / 1000) }
         / clock / { for (i = 1; i < NF; i++) if ($(i + 1) == "ms") c = sprintf("%.2f", $i / 1000) }
         END { printf "%s%s", f, c }'
}
printf "%-40s %-28s %s\n" binary window "first picture, s (each run)"
for bin in "${bins[@]}"; do
  for p in basic raymarch natural caustic_tex; do
    t=(); for ((k = 0; k < runs; k++)); do t+=("$(first "$bin" view "$here/scenes/lake.glib" --pack $p)"); done
    printf "%-40s %-28s %s\n" "$bin" "view, $p" "${t[*]}"
  done
  for packs in natural,raymarch raymarch,caustic_tex basic,natural,raymarch,caustic_tex; do
    t=(); for ((k = 0; k < runs; k++)); do t+=("$(first "$bin" compare-view "$here/scenes/lake.glib" --packs $packs)"); done
    printf "%-40s %-28s %s\n" "$bin" "compare-view, $packs" "${t[*]}"
  done
done
