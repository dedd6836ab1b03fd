#!/bin/sh
# man_options.sh TARN [PAGE]: rewrites the option lists of the man page
# (PAGE, default docs/tarn.1) from the commands' option tables: every block
# between
#   .\" BEGIN options: tarn help --roff NAME
#   .\" END options
# becomes what `TARN help --roff NAME` prints. The rest of the page is
# hand-written and left as it is. tests/test_man.c fails while a block
# differs from its table, and names this script.
#
#   cmake --build build && scripts/man_options.sh build/tarn
set -eu
tarn=${1:?usage: scripts/man_options.sh path/to/tarn [docs/tarn.1]}
page=${2:-$(dirname "$0")/../docs/tarn.1}
"$tarn" help --roff >/dev/null   # a tarn that knows --roff, before the page is touched
tmp=$(mktemp "$page.XXXXXX")
trap 'rm -f "$tmp"' EXIT
awk -v tarn="$tarn" '
    /^\.\\" BEGIN options: tarn help --roff / {
        print
        cmd = "\"" tarn "\" help --roff " $NF
        while ((cmd | getline line) > 0) print line
        if (close(cmd) != 0) { print "man_options.sh: " cmd " failed" > "/dev/stderr"; exit 1 }
        skip = 1
        next
    }
    /^\.\\" END options/ { skip = 0 }
    !skip { print }
' "$page" >"$tmp"
mv "$tmp" "$page"
trap - EXIT
