#!/bin/sh
# `make install` into a temporary root (DESTDIR), then the installed s42 run
# from another directory with nothing to point it at its plugins: it finds
# them beside itself (<exe>/../lib/s42/plugins), the bundled plugin programs
# run as the build tree's s42 runs them (the tooth search's OpenCV part
# included), and the installed man page renders.  Then, without building
# anything (make -n): another PREFIX rebuilds plugin.o with that prefix's
# plugin directory compiled in.
# usage: tests/plugins/install.sh S42 BUILD PREFIX
S42=$1
BUILD=${2:-build}
PREFIX=${3:-/usr/local}
. "$(dirname "$0")/../lib.sh"
t_init install
tmp=$T
src=$(pwd)
case $S42 in /*) tree=$S42 ;; *) tree=$src/$S42 ;; esac
# a make of its own: not a job of the make that runs the tests
unset MAKEFLAGS MFLAGS MAKELEVEL S42_PLUGIN_PATH

# everything is built already (the test target depends on it): install
# copies, and must rebuild nothing in the tree the other tests use
make --no-print-directory install DESTDIR="$tmp/root" PREFIX="$PREFIX" BUILD="$BUILD" S42="$S42" \
  >"$tmp/log" 2>&1 && ok || bad "make install: $(cat "$tmp/log")"
if grep -q '^cc \|^g++ \|^c++ ' "$tmp/log"; then bad "make install rebuilt something: $(grep '^cc\|^g++\|^c++' "$tmp/log" | head -2)"; else ok; fi
root=$tmp/root$PREFIX
for f in bin/s42 lib/s42/plugins/helix.so lib/s42/plugins/oscillation.so lib/s42/plugins/toothsearch.so \
         lib/s42/plugins/toothsearch/toothsearch-cv.so lib/s42/plugins/toothsearch/toothsearch-png.so \
         include/s42_plugin.h share/man/man1/s42.1 \
         share/bash-completion/completions/s42; do
  [ -f "$root/$f" ] && ok || bad "make install did not install $f"
done

# from another directory, with the programs copied there
mkdir -p "$tmp/work"
for n in reamer_rake helical_flute endmill_search; do
  for f in programs/$n.kp programs/$n.operator programs/$n.tool; do
    [ -f "$f" ] && cp "$f" "$tmp/work/"
  done
done
cd "$tmp/work" || exit 1
"$root/bin/s42" plugins >"$tmp/list" 2>&1
st=$?
[ $st -eq 0 ] && ok || bad "installed s42 plugins: status $st"
for p in helix oscillation toothsearch; do
  grep -q "^$p 1.0 (ABI 1.1) $root/lib/s42/plugins/$p.so$" "$tmp/list" && ok ||
    bad "installed s42 plugins does not find $p beside itself: $(cat "$tmp/list")"
done
if grep -q "no plugins found\|refused" "$tmp/list"; then bad "installed s42 plugins: $(cat "$tmp/list")"; else ok; fi
for n in reamer_rake helical_flute endmill_search; do
  set -- "$n.kp" --dump
  [ -f "$n.operator" ] && set -- "$@" --operator "$n.operator"
  [ -f "$n.tool" ] && set -- "$@" --tool "$n.tool"
  "$root/bin/s42" run "$@" >"$tmp/$n.installed" 2>"$tmp/err"
  st=$?
  [ $st -eq 0 ] && ok || bad "installed s42 run $n: status $st: $(head -3 "$tmp/err")"
  "$tree" run "$@" >"$tmp/$n.tree" 2>/dev/null
  cmp -s "$tmp/$n.installed" "$tmp/$n.tree" && ok || bad "$n: the installed s42's dump differs from the build tree's"
done
# the installed tooth search writes its images (its PNG writer beside it)
"$root/bin/s42" run endmill_search.kp --tool endmill_search.tool --operator endmill_search.operator \
  --dump-images "$tmp/img" >/dev/null 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && [ -s "$tmp/img/N3_section1_shot1.png" ] && ok ||
  bad "installed s42 run endmill_search --dump-images: status $st: $(head -3 "$tmp/err") $(ls "$tmp/img" 2>&1 | head -2)"
cd "$src" || exit 1

# the installed man page renders, and its FILES section says where plugins are
if command -v man >/dev/null 2>&1; then
  MANWIDTH=80 man -l "$root/share/man/man1/s42.1" >"$tmp/man" 2>"$tmp/err" && ok || bad "man -l: $(cat "$tmp/err")"
  grep -q "lib/s42/plugins" "$tmp/man" && grep -q "FILES" "$tmp/man" && ok || bad "the man page's FILES do not name lib/s42/plugins"
else
  echo "install: man is not here: the man page check was skipped"
fi

# another PREFIX is compiled into plugin.o (make -n: nothing is built)
make -n --no-print-directory install PREFIX=/elsewhere BUILD="$BUILD" S42="$S42" 2>/dev/null >"$tmp/n"
grep -q "S42_PLUGINDIR='\"/elsewhere/lib/s42/plugins\"'.* -o $BUILD/src/dialect/2c42/plugin.o src/dialect/2c42/plugin.c" "$tmp/n" && ok ||
  bad "make install PREFIX=/elsewhere would not rebuild plugin.o for that prefix"

t_done
