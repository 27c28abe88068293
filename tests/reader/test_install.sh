#!/bin/sh
# make install, checked from outside the build: install into a fresh prefix, (a) build
# reader/example.c with the installed header and library alone (pkg-config), run it on a real
# data.h5 and check its table; (b) the installed bhnsid lists its plugins, all of them found in
# <prefix>/lib/bhnsid; (c) --component reader installs the reader's files and nothing of the solver.
# usage: test_install.sh BUILD_DIR SOURCE_DIR WORK_DIR DATA.h5 [EXTRA_CFLAGS]
set -eu
build=$1 src=$2 work=$3 data=$4 extra=${5:-}
fail() { echo "FAIL: $*" >&2; exit 1; }
prefix=$work/install-prefix
rm -rf "$prefix" "$work/install-reader"
cmake --install "$build" --prefix "$prefix" > "$work/install.log"

# (a) The example against the installed reader only: no -I or -L into the source or build tree.
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
flags=$(pkg-config --cflags --libs bhnsid_reader) || fail "pkg-config does not find bhnsid_reader"
rest=$(echo "$flags" | sed "s#$prefix[^ ]*##g")  # the prefix itself lies under the build tree
case "$rest" in *"$src"*|*"$build"*) fail "pkg-config flags point into the tree: $flags" ;; esac
cp "$src/reader/example.c" "$work/example.c"
# shellcheck disable=SC2086
cc -std=c99 -Wall -Wextra -Werror $extra "$work/example.c" -o "$work/example" $flags -Wl,-rpath,"$prefix/lib"
out=$("$work/example" "$data") || fail "the example failed on $data"
echo "$out"
[ "$(echo "$out" | head -1)" = "x y z alp gxx rho" ] || fail "example header: $out"
[ "$(echo "$out" | wc -l)" -eq 4 ] || fail "example: expected 3 rows"
# Every value finite, alp in (0, 1], gxx >= 1 (phi >= 1 for this data), rho >= 0.
echo "$out" | tail -3 | awk '{ if (!($4 > 0 && $4 <= 1 && $5 >= 1 && $6 >= 0)) { print "bad row: " $0; exit 1 } }' \
  || fail "example values"
ldd "$work/example" | grep -q "$prefix/lib/libbhnsid_reader.so" || fail "the example did not link the installed library"

# (b) The installed solver, moved away from the build: its plugins come from <prefix>/lib/bhnsid.
plugins=$("$prefix/bin/bhnsid" plugins) || fail "installed bhnsid plugins failed"
echo "$plugins" | head -5
for p in grid multigrid puncture hamiltonian io_hdf5 star flow_corotating; do
  echo "$plugins" | grep -q "$p" || fail "installed bhnsid does not list $p"
done
echo "$plugins" | grep -q "$build/lib/bhnsid" && fail "installed bhnsid found plugins in the build tree"
echo "$plugins" | grep -q "^  $prefix/lib/bhnsid$" || fail "installed bhnsid does not search $prefix/lib/bhnsid"
[ -f "$prefix/lib/bhnsid/star.plot.py" ] || fail "no star.plot.py installed"
ls "$prefix/lib/bhnsid" | grep -q test && fail "a test-only plugin was installed"
ldd "$prefix/bin/bhnsid" | grep -q "libbhnsid_core.so => $prefix/bin/../lib/libbhnsid_core.so" || fail "bhnsid does not find the installed core"

# (c) The reader's component alone.
reader=$work/install-reader
cmake --install "$build" --prefix "$reader" --component reader > "$work/install-reader.log"
(cd "$reader" && find . -type f -o -type l | sort) > "$work/install-reader.list"
cat "$work/install-reader.list"
for f in include/bhnsid_reader.h lib/libbhnsid_reader.so lib/pkgconfig/bhnsid_reader.pc bin/bhnsid-export \
         share/bhnsid/python/bhnsid_reader.py; do
  [ -e "$reader/$f" ] || fail "--component reader did not install $f"
done
grep -q -e bhnsid_core -e "lib/bhnsid/" -e "bin/bhnsid$" "$work/install-reader.list" && fail "--component reader installed the solver"
echo "install: ok"
