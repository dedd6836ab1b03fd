#!/usr/bin/env bash
# The one window loop (viewer/ui/app.c) behind `tarn view` and `tarn
# compare-view`, under Xvfb, through both commands:
#   - hot reload survives a dependency in a directory that does not exist
#     yet: the scene names later/grey.frag, the test makes the folder and
#     the file while the window runs, and the program links (the script's
#     expects hold) without a restart;
#   - a lost context ends the window with exit 3 and the message;
#   - a save's reload message names the file saved;
#   - a save is compiled off the frame (viewer/ui/compile_job.h, issue #30):
#     the window draws frames between seeing the change and the new frame
#     and says it compiled off the frame; with TARN_COMPILE_ON_FRAME=1 (the
#     old way) the same measure reads 0 frames, so it can tell them apart;
#     a still picture shows the change, then its full-resolution frame once
#     the job has made that frame's code too.
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
scratch=$PWD/window-app-test
rm -rf "$scratch" && mkdir -p "$scratch" || fail "no scratch directory"
# our own X authority file: xvfb-run's temporary folder for one sometimes
# fails to be removed here (its exit 5 hides the program's exit status)
xvfb() { xvfb-run -a -f "$scratch/Xauthority" -s "-screen 0 1280x800x24" "$@"; }
cp "$src/tests/data/window/grey.vert" "$scratch/" || fail "no fixture"
sed 's#^Fragment grey.frag#Fragment later/grey.frag#' "$src/tests/data/window/scene.glib" > "$scratch/scene.glib"
grep -q "^Fragment later/grey.frag" "$scratch/scene.glib" || fail "the scene does not name later/grey.frag"
cat > "$scratch/rewatch.script" <<'SCRIPT'
frames 2
wait 5                     # the test makes later/grey.frag meanwhile
expect Flat uGrey 0.25     # the program linked: the new file was loaded
quit
SCRIPT

# $1: the name in messages; the rest: the command line.
missing_dir() {
    local name=$1; shift
    local log=$scratch/$name.log
    rm -rf "$scratch/later" "$log"
    # once the window has reported the missing file and started watching
    # (a second later; the script waits 5), make the folder and the file;
    # compare-view watches once every pack is loaded (its second loads
    # after the first frame: a folder made during that load was missed)
    local ready="cannot open 'later/grey.frag'"
    [ "$name" = compare-view ] && ready="compare-view: loaded world.glib"
    (for _ in $(seq 300); do grep -q "$ready" "$log" 2>/dev/null && break; sleep 0.1; done
     sleep 1
     mkdir "$scratch/later" && cp "$src/tests/data/window/grey.frag" "$scratch/later/") &
    local maker=$!
    (cd "$scratch" && xvfb "$@" --script rewatch.script >"$log" 2>&1)
    local rc=$?
    wait "$maker"
    cat "$log"
    # the first load failed, so a scripted run ends with exit 1 even when
    # the script's expects hold; a failed expect also exits 1, hence the log
    [ "$rc" -eq 1 ] || fail "$name exited $rc"
    grep -q "watching files" "$log" && fail "$name: the watcher refused the files"
    [ "$(grep -c 'Flat.uGrey holds the expected value' "$log")" -eq 1 ] ||
        fail "$name: no reload after the folder appeared"
    grep -q "reloaded [a-z]*\.glib (a missing folder appeared)" "$log" || fail "$name: the reload does not say why"
}
# compare-view draws packs, and a pack needs a scene that describes a world
# (a glman scene given packs is refused): the same scene with a Sun
world() { sed '2a Sun 0.4 0.8 -0.45  2.2 2.1 1.9' "$1" > "$2"; }
world "$scratch/scene.glib" "$scratch/world.glib"
missing_dir view "$bin" view scene.glib
missing_dir compare-view "$bin" compare-view world.glib --packs basic,basic --size 320x240

printf 'frames 20\nquit\n' > "$scratch/frames.script"
# $1: the name in messages; the rest: the command line.
lost_context() {
    local name=$1; shift
    local log=$scratch/$name-lost.log
    (cd "$scratch" && TARN_SIMULATE_CONTEXT_LOSS=2 xvfb "$@" --script frames.script >"$log" 2>&1)
    local rc=$?
    cat "$log"
    [ "$rc" -eq 3 ] || fail "$name: a lost context exited $rc, not 3"
    grep -q "the OpenGL context was lost" "$log" || fail "$name: no message for the lost context"
}
cp "$src/tests/data/window/grey.frag" "$scratch/grey.frag"
sed 's#^Fragment later/grey.frag#Fragment grey.frag#' "$scratch/scene.glib" > "$scratch/lost.glib"
lost_context view "$bin" view lost.glib
world "$scratch/lost.glib" "$scratch/lost-world.glib"
lost_context compare-view "$bin" compare-view lost-world.glib --packs basic,basic --size 320x240
# a save while the window runs: the reload message names the file saved
# (long enough for the compile job under a sanitizer: the save may land while
# it loads the scenes for the first time, and is compiled after that)
printf 'frames 2\nwait 12\nquit\n' > "$scratch/save.script"
saved_file_named() {
    local name=$1 glib=$2; shift 2
    local log=$scratch/$name-save.log
    rm -f "$log"
    (for _ in $(seq 300); do grep -q "loaded\|reloaded" "$log" 2>/dev/null && break; sleep 0.1; done
     sleep 1
     echo "// saved" >> "$scratch/grey.frag") &
    local saver=$!
    (cd "$scratch" && xvfb "$@" --script save.script >"$log" 2>&1)
    local rc=$?
    wait "$saver"
    cat "$log"
    [ "$rc" -eq 0 ] || fail "$name: exited $rc"
    grep -q "reloaded $glib (grey.frag changed)" "$log" || fail "$name: the reload message does not name grey.frag"
}
saved_file_named view lost.glib "$bin" view lost.glib
saved_file_named compare-view lost-world.glib "$bin" compare-view lost-world.glib --packs basic,basic --size 320x240
# $1: "job" or "frame" (TARN_COMPILE_ON_FRAME=1). The camera turns all
# along (orbit): a moving picture must keep its frames coming while the job
# compiles (a still one sleeps through the job, as it does without a script)
printf 'frames 2\norbit 0.002 0 1000000\nstamp on\nwait 12\nquit\n' > "$scratch/stamp.script"
compile_mode() {
    local mode=$1 log=$scratch/compile-$1.log
    rm -f "$log"
    # the save once the job has the scene loaded (--verbose says so; on the
    # frame there is no job): what a user's first edit meets
    local ready="compile job has the scene loaded"
    [ "$mode" = frame ] && ready="stamp on"
    (for _ in $(seq 600); do grep -q "$ready" "$log" 2>/dev/null && break; sleep 0.1; done
     sleep 1.5
     echo "float unusedBy$mode$(date +%N)() { return 1.0; }" >> "$scratch/grey.frag") &
    local saver=$!
    if [ "$mode" = frame ]; then export TARN_COMPILE_ON_FRAME=1; else unset TARN_COMPILE_ON_FRAME; fi
    (cd "$scratch" && xvfb "$bin" view lost.glib --verbose --script stamp.script >"$log" 2>&1)
    local rc=$?
    unset TARN_COMPILE_ON_FRAME
    wait "$saver"
    cat "$log"
    [ "$rc" -eq 0 ] || fail "compile $mode: exited $rc"
    local frames
    frames=$(sed -n 's/.*first frame after the reload swapped.*, \([0-9]*\) frames before it).*/\1/p' "$log" | head -1)
    [ -n "$frames" ] || fail "compile $mode: no stamp of the first frame after the reload"
    if [ "$mode" = job ]; then
        grep -q "reloaded lost.glib (grey.frag changed), compiled off the frame in" "$log" ||
            fail "the save was not compiled off the frame"
        [ "$frames" -ge 2 ] || fail "the window drew $frames frames while the save compiled (want 2 or more)"
    else
        grep -q "compiled off the frame" "$log" && fail "TARN_COMPILE_ON_FRAME=1 still compiled off the frame"
        [ "$frames" -eq 0 ] || fail "compiled on the frame, yet $frames frames were drawn before the reload"
    fi
}
# (Mesa's cache is what the job fills: on for this part whatever the caller set)
MESA_SHADER_CACHE_DISABLE=false compile_mode job
MESA_SHADER_CACHE_DISABLE=false compile_mode frame
# A still picture: the window shows the change once the job has the reduced
# frames' code, holds its full-resolution frame while the job makes that
# one's, and draws it when the job ends (a 1 ms budget keeps every changing
# frame reduced, so the hold is met): the picture ends at 100%.
printf 'budget 1\nframes 2\nstamp on\nwait 12\nresolution\nquit\n' > "$scratch/still.script"
still_log=$scratch/compile-still.log
rm -f "$still_log"
(for _ in $(seq 600); do grep -q "compile job has the scene loaded" "$still_log" 2>/dev/null && break; sleep 0.1; done
 sleep 1.5
 echo "float unusedByStill$(date +%N)() { return 1.0; }" >> "$scratch/grey.frag") &
saver=$!
(cd "$scratch" && MESA_SHADER_CACHE_DISABLE=false xvfb "$bin" view lost.glib --verbose --script still.script >"$still_log" 2>&1)
rc=$?
wait "$saver"
cat "$still_log"
[ "$rc" -eq 0 ] || fail "still: exited $rc"
grep -q "reloaded lost.glib (grey.frag changed), compiled off the frame in" "$still_log" ||
    fail "still: the save was not compiled off the frame"
grep -q "first frame after the reload swapped" "$still_log" || fail "still: no stamp of the first frame after the reload"
grep -q "resolution [0-9]*x[0-9]* (100%)" "$still_log" ||
    fail "still: the picture did not end at full resolution (the held full frame was never drawn)"
echo "window app test: ok"
