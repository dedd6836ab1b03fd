#!/usr/bin/env bash
# Recording in `tarn view` under Xvfb, and its replay:
#   - Shift+R (a real key press) starts tarn-DATE-N.session in the current
#     directory; Space, a scripted slider change and a scripted camera move
#     become its events, and closing the window ends it with `end`;
#   - --record FILE records from the start, and `tarn record` replays that
#     file to the value the window had (the frame's grey is the slider's).
set -u
bin=$1; src=$2
command -v xvfb-run >/dev/null || { echo "skip: xvfb-run is missing (apt-get install xvfb)"; exit 77; }
command -v python3 >/dev/null || { echo "skip: python3 is missing (presses keys, reads PNGs)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
scratch=$PWD/window-record-test
rm -rf "$scratch" && mkdir -p "$scratch" || fail "no scratch directory"
xvfb() { xvfb-run -a -f "$scratch/Xauthority" -s "-screen 0 1280x800x24" "$@"; }
# the keys come meanwhile: Shift+R until a session file appears, then Space
cat > "$scratch/keys.script" <<'SCRIPT'
wait 8
set Flat uGrey 0.6
camera 0 0 0 3 0.5 0.2
frames 5
quit
SCRIPT
# Shift+R toggles: a second press before a slow window answered the first
# would stop the recording, so the keys start once the scene has loaded
# and x_keys waits 3 s for the file before pressing again
keys_run='
    cd "$3" || exit 1
    "$1" view "$2/tests/data/window/scene.glib" --size 320x240 --script keys.script 2>view.log &
    view=$!
    for _ in $(seq 100); do grep -q "^tarn: loaded" view.log && break; sleep 0.1; done
    sleep 1
    python3 "$2/tests/x_keys.py" "tarn-*.session" shift+r space 3
    keys=$?
    wait $view
    view_rc=$?
    [ "$keys" -eq 77 ] && exit 77
    [ "$keys" -eq 0 ] && [ "$view_rc" -eq 0 ]'
xvfb bash -c "$keys_run" keys_run "$bin" "$src" "$scratch" > "$scratch/keys.log" 2>&1
rc=$?
cat "$scratch/keys.log" "$scratch/view.log"
if [ "$rc" -eq 77 ]; then
    echo "window record test: the key run skipped (no libXtst)"
else
    [ "$rc" -eq 0 ] || fail "the Shift+R run failed ($rc)"
    session=$(ls "$scratch"/tarn-*.session 2>/dev/null | tail -1)
    [ -n "$session" ] || fail "Shift+R wrote no tarn-*.session in the current directory"
    cat "$session"
    grep -q "^tarn: recording to tarn-.*\.session$" "$scratch/view.log" || fail "the recording was not announced"
    grep -qx "tarn-session 1" "$session" || fail "no format line"
    grep -q "^scene /.*/tests/data/window/scene.glib$" "$session" || fail "no absolute scene path"
    grep -qx "size 320 240" "$session" || fail "no window size"
    grep -q "^time " "$session" || fail "no start time"
    grep -q "^t=[0-9.]* pause 1$" "$session" || fail "Space is not a pause event"
    grep -q "^t=[0-9.]* slider Flat uGrey 0.6" "$session" || fail "the slider change is not an event"
    grep -q "^t=[0-9.]* camera 0 0 0 3 0.5 0.2" "$session" || fail "the camera move is not an event"
    tail -1 "$session" | grep -q "^t=[0-9.]* end$" || fail "closing the window did not end the session"
    echo "window record test (Shift+R): ok"
fi

# --record from the start; the replay ends on the window's last value
printf 'frames 3\nset Flat uGrey 0.6\nwait 0.5\nquit\n' > "$scratch/set.script"
(cd "$scratch" && xvfb "$bin" view "$src/tests/data/window/scene.glib" --size 320x240 \
    --record take.session --script set.script > take.log 2>&1)
rc=$?
cat "$scratch/take.log" "$scratch/take.session"
[ "$rc" -eq 0 ] || fail "tarn view --record exited $rc"
grep -q "^t=[0-9.]* slider Flat uGrey 0.6" "$scratch/take.session" || fail "--record missed the slider"
grep -q "recorded [0-9]* events" "$scratch/take.log" || fail "the end of the recording was not announced"
(cd "$scratch" && "$bin" record take.session -o take/ --size 32x24 --fps 30) || fail "tarn record failed"
last=$(ls "$scratch"/take/frame-*.png | tail -1)
px=$(python3 "$src/tests/png_probe.py" "$last" 16 12 | grep '^pixel') || fail "cannot read $last"
echo "$px"
[ "$px" = "pixel 16 12 153 153 153 255" ] || fail "the replay's last frame is not uGrey 0.6 (153): $px"
echo "window record test (--record, replay): ok"
