#!/usr/bin/env bash
# Called when the sanitizer build's ctest failed. LeakSanitizer checks for
# leaks at exit from a tracer thread that stops every other thread; with
# Mesa llvmpipe's threads it sometimes crashes itself ("Tracer caught
# signal 11" then "LeakSanitizer has encountered a fatal error"): seen once
# in test_soak in CI, after the test's own checks all passed; the same test
# passed when run again. That is the tool failing, not a finding:
# a test that failed only so runs once more, whole, and must pass then.
# Any other failure stands, and this script exits 1.
#
# Usage: scripts/lsan_rerun.sh BUILD_DIR
set -uo pipefail
dir=$1
failed_list=$dir/Testing/Temporary/LastTestsFailed.log
log=$dir/Testing/Temporary/LastTest.log
[ -s "$failed_list" ] && [ -s "$log" ] || { echo "lsan_rerun: no ctest logs in $dir"; exit 1; }
names=()
while IFS=: read -r _ name; do
    # the test's section of the log: from "N/M Testing: NAME" to its end time
    section=$(awk -v n="$name" '$0 ~ "Testing: " n "$" {on=1} on {print} on && $0 ~ "^\"" n "\" end time" {exit}' "$log")
    if ! grep -q "Tracer caught signal" <<<"$section" ||
       ! grep -q "LeakSanitizer has encountered a fatal error" <<<"$section"; then
        echo "lsan_rerun: $name failed for another reason than LeakSanitizer's tracer: the failure stands"
        exit 1
    fi
    names+=("$name")
done <"$failed_list"
[ "${#names[@]}" -gt 0 ] || exit 1
regex="^($(IFS='|'; echo "${names[*]}"))\$"
echo "lsan_rerun: LeakSanitizer's tracer crashed at exit in: ${names[*]}; running them once more"
cd "$dir" && ctest --output-on-failure --no-tests=error -R "$regex"
