#!/usr/bin/env bash
# `tarn record SESSION -o OUT.mp4` through the ffmpeg program: the video
# has one frame per 1/fps of the session (ffprobe counts them) at the size
# asked for (an odd one padded to even for yuv420p). Skipped when ffmpeg or
# ffprobe is missing (apt-get install ffmpeg).
set -u
bin=$1; src=$2
command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null ||
    { echo "skip: ffmpeg/ffprobe are missing (apt-get install ffmpeg)"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
scratch=$PWD/record-mp4-test
rm -rf "$scratch" && mkdir -p "$scratch" || fail "no scratch directory"
cat > "$scratch/s.session" <<SESSION
tarn-session 1
scene $src/tests/data/window/scene.glib
size 32 24
time 0
t=0.500 slider Flat uGrey 0.75
t=1.500 end
SESSION
# $1: fps, $2: size, $3: the frames expected, $4: the video's W,H
check() {
    rm -f "$scratch/v.mp4"
    env -u DISPLAY "$bin" record "$scratch/s.session" -o "$scratch/v.mp4" --fps "$1" --size "$2" ||
        fail "tarn record exited $?"
    local got
    got=$(ffprobe -v error -count_frames -select_streams v:0 \
          -show_entries stream=nb_read_frames,width,height -of csv=p=0 "$scratch/v.mp4") ||
        fail "ffprobe cannot read the video"
    echo "fps $1, size $2: $got"
    [ "$got" = "$4,$3" ] || fail "expected $4 with $3 frames, got $got"
}
check 10 32x24 15 32,24
check 24 33x25 36 34,26
echo "record mp4 test: ok"
