#!/bin/sh
# Plugins from the outside: the minimal plugin of the README built against
# the installed header alone; --plugins and S42_PLUGIN_PATH; refused
# plugins in `s42 plugins`; E-PLUGIN when the plugin directory is missing;
# and OpenCV never loaded by a program without G10/G11 (LD_DEBUG=files
# lists every library the dynamic loader maps).
# usage: tests/plugins/run.sh S42 BUILD
S42=$1
BUILD=${2:-build}
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL plugins: $*"; fail=$((fail + 1)); }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM

# the header as `make install` installs it (checked with make -n, which
# builds nothing), then a plugin that sees nothing else of s42
make -n --no-print-directory install DESTDIR="$tmp/root" PREFIX=/usr BUILD="$BUILD" S42="$S42" 2>/dev/null |
  grep -q 'include/s42_plugin.h .*/usr/include/s42_plugin.h' && ok || bad "make install does not install s42_plugin.h"
install -D -m 644 include/s42_plugin.h "$tmp/root/usr/include/s42_plugin.h"
mkdir -p "$tmp/p" "$tmp/bin"
cp docs/plugin-example/hello.c "$tmp/hello.c"
if (cd "$tmp" && cc -std=c11 -Wall -Wextra -Werror -shared -fPIC -I"$tmp/root/usr/include" -o p/hello.so hello.c); then
  ok
else
  bad "hello.c does not build against the installed header"
fi
printf '№1 R0+0 ^\n№7 M11 ^\n№8 M02 ^\n' > "$tmp/hello.kp"
out=$("$S42" run "$tmp/hello.kp" --plugins "$tmp/p" --dump 2>"$tmp/err")
case $out in *'"r":[7,'*) ok ;; *) bad "M11 did not set R0: $out" ;; esac
grep -q "hello from block 7" "$tmp/err" && ok || bad "no log line: $(cat "$tmp/err")"
out=$(S42_PLUGIN_PATH="/nonexistent:$tmp/p" "$S42" run "$tmp/hello.kp" --dump 2>/dev/null)
case $out in *'"r":[7,'*) ok ;; *) bad "S42_PLUGIN_PATH not searched" ;; esac
"$S42" plugins --plugins "$tmp/p" | grep -q "^hello 1.0" && ok || bad "s42 plugins does not list hello"

# refused fixtures are listed with the reason
"$S42" plugins --plugins "$BUILD/test-plugins/wrongabi" | grep -q "built for plugin ABI 2.0; this s42 has ABI 1.1" &&
  ok || bad "wrong ABI not reported"
"$S42" plugins --plugins "$BUILD/test-plugins/noentry" | grep -q "has no entry symbol" && ok || bad "no entry not reported"

# no plugins at all: a copy of s42 away from the build tree
cp "$S42" "$tmp/bin/s42"
printf '№1 G12 G17 X+0 Y+0 I-1000 J+0 Z+100 F100 ^\n№2 M02 ^\n' > "$tmp/helix.kp"
"$tmp/bin/s42" run "$tmp/helix.kp" --plugins "$tmp/none" >/dev/null 2>"$tmp/err"
st=$?
[ $st -eq 1 ] && ok || bad "missing plugin: status $st, want 1"
grep -q "G12 (helical interpolation) needs the helix plugin, which was not found in $tmp/none" "$tmp/err" &&
  grep -q "E-PLUGIN" "$tmp/err" && ok || bad "missing plugin message: $(cat "$tmp/err")"
"$tmp/bin/s42" check "$tmp/hello.kp" >/dev/null 2>"$tmp/err"
grep -q "M11 is not a function of the 2С42 or of a plugin found" "$tmp/err" && ok || bad "M11 without plugin: $(cat "$tmp/err")"

# OpenCV is the tooth search's alone: never mapped without G10/G11, even
# with --tool given and the light toothsearch.so loaded to read its
# descriptor; a program that searches maps it when it starts
LD_DEBUG=files "$S42" run programs/reamer_rake.kp --tool tests/toothsearch/t004_reamer_seed.tool >/dev/null 2>"$tmp/ld"
if grep -q "opencv" "$tmp/ld"; then bad "a program without G10/G11 loaded OpenCV"; else ok; fi
grep -q "oscillation.so" "$tmp/ld" && ok || bad "LD_DEBUG shows no plugin loading (the check above proves nothing)"
grep -q "toothsearch.so" "$tmp/ld" && ok || bad "the light toothsearch.so was not read"
if grep -q "toothsearch-cv.so" "$tmp/ld"; then bad "a program without G10/G11 loaded toothsearch-cv.so"; else ok; fi
LD_DEBUG=files "$S42" plugins >/dev/null 2>"$tmp/ld"
if grep -q "opencv" "$tmp/ld"; then bad "s42 plugins loaded OpenCV"; else ok; fi
printf '№1 G10 D1+60000 ^\n№2 M02 ^\n' > "$tmp/g10.kp"
printf 'key PUSK\nkey PS\nkey PUSK\n' > "$tmp/g10.op"
LD_DEBUG=files "$S42" run "$tmp/g10.kp" --tool tests/toothsearch/t004_reamer_seed.tool --operator "$tmp/g10.op" \
  >/dev/null 2>"$tmp/ld"
st=$?
[ $st -eq 0 ] && ok || bad "G10 run: status $st"
grep -q "libopencv_core" "$tmp/ld" && grep -q "toothsearch/toothsearch-cv.so" "$tmp/ld" && ok ||
  bad "a G10 program did not map OpenCV (LD_DEBUG=files)"

# the tooth search without its heavy part: the plugin refuses to start with
# the reason, and the block is E-PLUGIN; programs without G10 are not hurt
mkdir -p "$tmp/light"
cp "$BUILD/plugins/toothsearch.so" "$tmp/light/"
"$tmp/bin/s42" run "$tmp/g10.kp" --plugins "$tmp/light" --tool tests/toothsearch/t004_reamer_seed.tool \
  --operator "$tmp/g10.op" >/dev/null 2>"$tmp/err"
st=$?
[ $st -eq 1 ] && ok || bad "no toothsearch-cv.so: status $st, want 1"
grep -q "the toothsearch plugin ($tmp/light/toothsearch.so) failed to start: its OpenCV part cannot be loaded: .*toothsearch/toothsearch-cv.so" "$tmp/err" &&
  grep -q "E-PLUGIN" "$tmp/err" && ok || bad "no toothsearch-cv.so: $(cat "$tmp/err")"
printf '№1 G01 X+10 F100 ^\n№2 M02 ^\n' > "$tmp/plain.kp"
"$tmp/bin/s42" run "$tmp/plain.kp" --plugins "$tmp/light" --tool tests/toothsearch/t004_reamer_seed.tool >/dev/null 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && ok || bad "a program without G10 beside a broken toothsearch: status $st: $(cat "$tmp/err")"

echo "plugins: $pass passed, $fail failed"
[ $fail -eq 0 ]
