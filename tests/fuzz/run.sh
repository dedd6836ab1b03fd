#!/usr/bin/env bash
# A short libFuzzer run of one target (ctest in a TARN_FUZZ build):
#   run.sh FUZZER NAME SECONDS TESTS_FUZZ_DIR
# It starts from the seed corpus and the regressions (read-only: new inputs
# go to fuzz-work/NAME), and prints libFuzzer's final figures. A crash, leak,
# sanitizer report, timeout (10 s on one input) or out-of-memory fails it and
# leaves the input in fuzz-artifacts/.
set -u
bin=$1; name=$2; secs=$3; src=$4
work=fuzz-work/$name
mkdir -p "$work" fuzz-artifacts
dirs=("$work" "$src/corpus_$name")
[ -d "$src/regress_$name" ] && dirs+=("$src/regress_$name")
# the repository's own files of the target's kind seed it too, as they are
# now (a copy of each, flattened: libFuzzer reads the directory)
case "$name" in
    glib) pattern='.*\.glib' ;;
    shader) pattern='.*\.\(vert\|frag\|geom\|glsl\|tesc\|tese\)' ;;
    obj) pattern='.*\.obj' ;;
    *) pattern= ;;
esac
if [ -n "$pattern" ]; then
    seeds=fuzz-work/repo-$name
    rm -rf "$seeds" && mkdir -p "$seeds"
    root=$(cd "$src/../.." && pwd)
    find "$root/packs" "$root/scenes" "$root/tests/data" "$root/data" -type f -regex "$pattern" | while read -r f; do
        rel=${f#"$root"/}
        cp "$f" "$seeds/${rel//\//_}"
    done
    dirs+=("$seeds")
fi
dict=()
[ -f "$src/$name.dict" ] && dict=(-dict="$src/$name.dict")
"$bin" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 \
    -artifact_prefix="fuzz-artifacts/$name-" "${dict[@]}" "${dirs[@]}" 2>&1 | tail -n 40
rc=${PIPESTATUS[0]}
if [ "$rc" -ne 0 ]; then
    echo "FAIL: fuzz_$name found a problem (exit $rc): the input is in $(pwd)/fuzz-artifacts/;"
    echo "      fix it, then add the input to tests/fuzz/regress_$name/ so that ctest replays it"
    exit 1
fi
echo "fuzz_$name: no crash in ${secs} s"
