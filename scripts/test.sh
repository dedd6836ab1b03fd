#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (ctest), including
# glslang validation of every pack and the window test under Xvfb; then the
# whole suite again under AddressSanitizer + UBSan (build-asan), then a
# short run of each libFuzzer target (build-fuzz, clang). Every build is
# made with -Werror (TARN_WERROR): a warning fails CI.
#
# Arguments go to ctest (e.g. -R test_glib). TARN_TEST_SANITIZE=0 or
# TARN_TEST_FUZZ=0 leave out the second or third part (CI runs all three).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
jobs=$(nproc)
start=$(date +%s)
stage() { echo "== tarn tests: $1 ($(( $(date +%s) - start )) s so far)"; }

stage "build"
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTARN_WERROR=ON >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure -j"$jobs" "$@")

if [ "${TARN_TEST_SANITIZE:-1}" != 0 ]; then
    stage "build-asan: every test under AddressSanitizer and UndefinedBehaviorSanitizer"
    cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTARN_SANITIZE=ON -DTARN_WERROR=ON >/dev/null
    cmake --build build-asan -j"$jobs"
    (cd build-asan && ctest --output-on-failure -j"$jobs" "$@") || scripts/lsan_rerun.sh build-asan
fi

if [ "${TARN_TEST_FUZZ:-1}" != 0 ]; then
    stage "build-fuzz: the fuzz targets, ${TARN_FUZZ_SECONDS:-20} s each"
    cmake -S . -B build-fuzz -DTARN_FUZZ=ON -DTARN_WERROR=ON -DCMAKE_C_COMPILER=clang \
          -DTARN_FUZZ_SECONDS="${TARN_FUZZ_SECONDS:-20}" >/dev/null
    cmake --build build-fuzz -j"$jobs"
    (cd build-fuzz && ctest --output-on-failure -j"$jobs")
fi
stage "all passed"
