#!/usr/bin/env bash
# Installs what tarn needs to build, run and test, from Debian's packages only.
# Idempotent: it asks dpkg first and prints nothing when everything is there.
# ffmpeg is a program tarn runs, not a library it links: `tarn record` pipes
# raw frames to it (any codec it has; PNG frames when it is missing).
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libglfw3-dev glslang-dev glslang-tools libcglm-dev
  libopenimageio-dev libimgui-dev
  libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  xvfb xauth libxtst6 python3   # the window tests: a real window, keys and mouse sent through XTest
  ffmpeg
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "tarn: installing missing Debian packages: ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
