#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then the installed tarn, run
# from outside the source tree with TARN_ROOT unset, must use the prefix's
# packs and scenes and never the source tree's. Proof, two ways:
#   - `tarn --version` names PREFIX/share/tarn as its data folder;
#   - with one pack deleted from the prefix (the source tree keeps it),
#     the installed tarn reports it missing, naming PREFIX/share/tarn/packs.
# Then the prefix is moved: the install still finds its own data.
set -u
cmake=$1; build=$2; src=$3
tmp=$(cd "$(mktemp -d /tmp/tarn-install-test-XXXXXX)" && pwd -P)   # tarn prints real paths
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
cd "$tmp" || exit 1
unset TARN_ROOT
export XDG_CACHE_HOME="$tmp/cache" HOME="$tmp/home"   # nothing of the user's is read or written

"$cmake" --install "$build" --prefix "$tmp/prefix" >install.log 2>&1 || { cat install.log; fail "cmake --install"; }
for f in bin/tarn share/tarn/packs/basic/pack.glib share/tarn/packs/common share/tarn/scenes/pond.glib \
         share/tarn/scenes/hard share/man/man1/tarn.1 share/applications/tarn.desktop \
         share/mime/packages/tarn-glib.xml; do
    [ -e "$tmp/prefix/$f" ] || fail "not installed: $f"
done
grep -q '^Exec=tarn view %f$' "$tmp/prefix/share/applications/tarn.desktop" || fail "tarn.desktop: Exec"
grep -q '^MimeType=text/x-glib;$' "$tmp/prefix/share/applications/tarn.desktop" || fail "tarn.desktop: MimeType"
grep -q 'type="text/x-glib"' "$tmp/prefix/share/mime/packages/tarn-glib.xml" || fail "tarn-glib.xml: type"
if command -v desktop-file-validate >/dev/null; then
    desktop-file-validate "$tmp/prefix/share/applications/tarn.desktop" || fail "desktop-file-validate"
fi
if command -v xmllint >/dev/null; then
    xmllint --noout "$tmp/prefix/share/mime/packages/tarn-glib.xml" || fail "tarn-glib.xml is not XML"
fi
if command -v update-mime-database >/dev/null; then   # the database shared-mime-info builds from it
    cp -r "$tmp/prefix/share/mime" "$tmp/mime"
    update-mime-database "$tmp/mime" >/dev/null 2>&1 || fail "update-mime-database rejects tarn-glib.xml"
    grep -q 'text/x-glib:\*\.glib' "$tmp/mime/globs2" || fail "mime: no *.glib glob"
    grep -q 'text/x-glib' "$tmp/mime/magic" || fail "mime: no magic"
fi

# which data: the prefix's
tarn=$tmp/prefix/bin/tarn
"$tarn" --version >version.txt 2>&1 || { cat version.txt; fail "tarn --version"; }
cat version.txt
grep -Eq '^tarn [0-9]+\.[0-9]+\.[0-9]+$' version.txt || fail "--version: no version line"
grep -qx "data: $tmp/prefix/share/tarn" version.txt || fail "--version: not the prefix's data"

# the installed scene, rendered
"$tarn" render "$tmp/prefix/share/tarn/scenes/pond.glib" -o x.png --size 64x48 >render.log 2>&1
rc=$?
cat render.log
[ "$rc" -eq 3 ] && { echo "skip: no OpenGL context"; exit 77; }
[ "$rc" -eq 0 ] || fail "installed tarn render exited $rc"
[ -s x.png ] || fail "no x.png"

# a pack gone from the prefix is gone for the installed tarn
[ -e "$src/packs/basic/pack.glib" ] || fail "the source tree has no packs/basic"
rm -rf "$tmp/prefix/share/tarn/packs/basic"
"$tarn" render "$tmp/prefix/share/tarn/scenes/lake.glib" --pack basic -o y.png --size 64x48 >nopack.log 2>&1
rc=$?
cat nopack.log
[ "$rc" -ne 0 ] || fail "the installed tarn found packs/basic, deleted from the prefix: it read another tree"
grep -q "no pack 'basic' in $tmp/prefix/share/tarn/packs" nopack.log || fail "the message names another packs folder"

# a moved install finds its own data
mv "$tmp/prefix" "$tmp/moved"
"$tmp/moved/bin/tarn" --version | grep -qx "data: $tmp/moved/share/tarn" || fail "moved: not its own data"
"$tmp/moved/bin/tarn" render "$tmp/moved/share/tarn/scenes/pond.glib" -o z.png --size 64x48 >/dev/null 2>&1 ||
    fail "moved: render"
[ -s z.png ] || fail "moved: no z.png"
echo "install test: ok"
