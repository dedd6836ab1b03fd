#!/usr/bin/env bash
# Installs what is missing, builds, and runs tarn on its default scene:
# a window when there is a display, else an image (the path is printed).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$(nproc)"
exec ./build/tarn "$@"
