#!/bin/sh
# Plugins from the outside: the minimal plugin of the README built against
# the installed header alone; --plugins and S42_PLUGIN_PATH; refused
# plugins in `s42 plugins` (a FIFO, a directory or a looping link named
# *.so among them); E-PLUGIN when the plugin directory is missing;
# a plugin that crashes in a callback (the run ends with E-PLUGIN, the
# terminal goes on); and OpenCV never loaded by a program without G10/G11, its imgcodecs by
# none without --dump-images (LD_DEBUG=files lists every library the
# dynamic loader maps).
# usage: tests/plugins/run.sh S42 BUILD
S42=$1
BUILD=${2:-build}
. "$(dirname "$0")/../lib.sh"
t_init plugins
tmp=$T

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
# with --tool given; such a program does not even open toothsearch.so (it
# opens the files of the plugins it uses); a program that searches maps
# OpenCV when it starts
LD_DEBUG=files "$S42" run programs/reamer_rake.kp --tool tests/toothsearch/t004_reamer_seed.tool >/dev/null 2>"$tmp/ld"
if grep -q "opencv" "$tmp/ld"; then bad "a program without G10/G11 loaded OpenCV"; else ok; fi
grep -q "oscillation.so" "$tmp/ld" && ok || bad "LD_DEBUG shows no plugin loading (the check above proves nothing)"
if grep -q "toothsearch.so\|helix.so" "$tmp/ld"; then bad "a program with only G07/M13/M14 opened toothsearch.so or helix.so"; else ok; fi
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
# the measurement needs OpenCV's core and imgproc; imgcodecs (its some 120
# libraries) comes with the PNG writer, toothsearch-png.so, for
# --dump-images alone
if grep -q "imgcodecs\|toothsearch-png.so" "$tmp/ld"; then
  bad "a G10 program without --dump-images loaded imgcodecs: $(grep -o 'file=[^ ]*\(imgcodecs\|png\.so\)[^ ]*' "$tmp/ld" | sort -u | tr '\n' ' ')"
else
  ok
fi
grep -q "libopencv_imgproc" "$tmp/ld" && ok || bad "a G10 program did not map imgproc (the check above proves nothing)"
LD_DEBUG=files "$S42" run "$tmp/g10.kp" --tool tests/toothsearch/t004_reamer_seed.tool --operator "$tmp/g10.op" \
  --dump-images "$tmp/img" >/dev/null 2>"$tmp/ld"
st=$?
[ $st -eq 0 ] && [ -s "$tmp/img/N1_section1_shot1.png" ] && ok || bad "G10 run with --dump-images: status $st: $(ls "$tmp/img" 2>&1 | head -3)"
grep -q "libopencv_imgcodecs" "$tmp/ld" && grep -q "toothsearch/toothsearch-png.so" "$tmp/ld" && ok ||
  bad "a G10 program with --dump-images did not load the PNG writer and imgcodecs"

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
# the heavy part without the PNG writer: G10 runs; --dump-images is refused
# at the start with the reason
mkdir -p "$tmp/nopng/toothsearch"
cp "$BUILD/plugins/toothsearch.so" "$tmp/nopng/"
cp "$BUILD/plugins/toothsearch/toothsearch-cv.so" "$tmp/nopng/toothsearch/"
"$tmp/bin/s42" run "$tmp/g10.kp" --plugins "$tmp/nopng" --tool tests/toothsearch/t004_reamer_seed.tool \
  --operator "$tmp/g10.op" >/dev/null 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && ok || bad "no toothsearch-png.so, no --dump-images: status $st: $(cat "$tmp/err")"
"$tmp/bin/s42" run "$tmp/g10.kp" --plugins "$tmp/nopng" --tool tests/toothsearch/t004_reamer_seed.tool \
  --operator "$tmp/g10.op" --dump-images "$tmp/img3" >/dev/null 2>"$tmp/err"
st=$?
[ $st -eq 1 ] && ok || bad "no toothsearch-png.so, --dump-images: status $st, want 1"
grep -q "the toothsearch plugin ($tmp/nopng/toothsearch.so) failed to start: no PNG writer for --dump-images: .*toothsearch/toothsearch-png.so" "$tmp/err" &&
  ok || bad "no toothsearch-png.so, --dump-images: $(cat "$tmp/err")"

# A plugin file is opened only for a program that needs a function it may
# provide, and then first in a child (the probe), so a constructor that
# crashes, calls _exit(0) or hangs costs a refusal, not the command.  The
# badctor fixture does what its file name says; marker*.so writes $S42_MARKER.
so="$BUILD/test-plugins/badctor/badctor.so"
mkdir -p "$tmp/bad" "$tmp/hang" "$tmp/hx" "$tmp/only-bad"
for n in crash exit marker; do cp "$so" "$tmp/bad/$n.so"; done
cp "$so" "$tmp/only-bad/crash.so"
cp "$so" "$tmp/only-bad/exit.so"
cp "$so" "$tmp/hang/hang.so"
cp "$so" "$tmp/hx/helix.so"
export S42_MARKER="$tmp/marker"
rm -f "$S42_MARKER"
# a core program: run, check, disasm and plot unaffected, no plugin file
# of any directory opened (LD_DEBUG=files lists what the loader maps)
LD_DEBUG=files "$S42" run "$tmp/plain.kp" --plugins "$tmp/bad" --dump >"$tmp/out" 2>"$tmp/ld"
st=$?
[ $st -eq 0 ] && grep -q '"status":"end"' "$tmp/out" && ok || bad "core run beside broken plugins: status $st: $(head -c 300 "$tmp/out")"
if grep -q "$tmp/bad/\|/plugins/[a-z]*\.so" "$tmp/ld"; then bad "a core program opened a plugin file: $(grep '\.so' "$tmp/ld" | grep -v '/lib/' | head -3)"; else ok; fi
"$S42" check "$tmp/plain.kp" --plugins "$tmp/bad" >/dev/null 2>"$tmp/err" && ok || bad "core check beside broken plugins: $(cat "$tmp/err")"
"$S42" disasm "$tmp/plain.kp" --plugins "$tmp/bad" >"$tmp/out" 2>"$tmp/err" && [ -s "$tmp/out" ] && ok ||
  bad "core disasm beside broken plugins: $(cat "$tmp/err")"
[ -e "$S42_MARKER" ] && bad "a core program loaded marker.so" || ok
# G12: the helix plugin's file, and no other
"$S42" run "$tmp/helix.kp" --plugins "$tmp/bad" --dump >"$tmp/out" 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && grep -q '"z":100' "$tmp/out" && ok || bad "G12 beside broken plugins: status $st: $(cat "$tmp/err")"
[ -e "$S42_MARKER" ] && bad "a G12 program loaded marker.so" || ok
# a function the language does not have: every file in order until one has
# it (crash.so and exit.so refused on the way, marker.so provides G53)
printf '№1 G53 ^\n№2 M02 ^\n' > "$tmp/g53.kp"
"$S42" run "$tmp/g53.kp" --plugins "$tmp/bad" --dump >"$tmp/out" 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && grep -q '"status":"end"' "$tmp/out" && ok || bad "G53 from marker.so: status $st: $(cat "$tmp/err")"
grep -q "^marker$" "$S42_MARKER" 2>/dev/null && ok || bad "G53 did not load marker.so"
"$S42" check "$tmp/g53.kp" --plugins "$tmp/only-bad" 2>"$tmp/err"
st=$?
[ $st -eq 1 ] && grep -q "g53.kp:1:4: error: N1: G53 is not a function of the 2С42 or of a plugin found \[E-FUNC\]" "$tmp/err" &&
  grep -q "g53.kp:1:4: note: N1: the plugin file $tmp/only-bad/crash.so cannot be used: its constructor crashed: signal 11 (SIGSEGV)" "$tmp/err" &&
  grep -q "note: N1: the plugin file $tmp/only-bad/exit.so cannot be used: loading it ended the process: exit 0" "$tmp/err" &&
  ok || bad "G53 with only broken files: status $st: $(cat "$tmp/err")"
# s42 plugins probes every file and lists the broken ones with the reason
"$S42" plugins --plugins "$tmp/bad" >"$tmp/out" 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && ok || bad "s42 plugins beside broken plugins: status $st"
grep -q "^refused: $tmp/bad/crash.so cannot be used: its constructor crashed: signal 11 (SIGSEGV)$" "$tmp/out" &&
  grep -q "^refused: $tmp/bad/exit.so cannot be used: loading it ended the process: exit 0$" "$tmp/out" &&
  grep -q "^marker 0.1 (ABI 1.1) $tmp/bad/marker.so$" "$tmp/out" && grep -q "^helix 1.0" "$tmp/out" && ok ||
  bad "s42 plugins beside broken plugins: $(cat "$tmp/out")"
"$S42" plugins --plugins "$tmp/hang" >"$tmp/out" 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && grep -q "^refused: $tmp/hang/hang.so cannot be used: loading it did not end within 5 s$" "$tmp/out" && ok ||
  bad "a constructor that hangs: status $st: $(cat "$tmp/out")"
# a program that needs a broken plugin (a helix.so that crashes, away from
# the build tree's good one): E-PLUGIN naming the file and why, and the dump
S42_BADCTOR=crash "$tmp/bin/s42" run "$tmp/helix.kp" --plugins "$tmp/hx" --dump >"$tmp/out" 2>"$tmp/err"
st=$?
[ $st -eq 1 ] && grep -q "G12 (helical interpolation) needs the helix plugin: $tmp/hx/helix.so cannot be used: its constructor crashed: signal 11 (SIGSEGV) \[E-PLUGIN\]" "$tmp/err" &&
  grep -q '"status":"error","error":{"code":"E-PLUGIN"' "$tmp/out" && ok || bad "a crashing helix.so: status $st: $(cat "$tmp/err")"
S42_BADCTOR=exit "$tmp/bin/s42" run "$tmp/helix.kp" --plugins "$tmp/hx" --dump >"$tmp/out" 2>"$tmp/err"
st=$?
[ $st -eq 1 ] && grep -q "needs the helix plugin: $tmp/hx/helix.so cannot be used: loading it ended the process: exit 0" "$tmp/err" &&
  grep -q '"code":"E-PLUGIN"' "$tmp/out" && ok || bad "a helix.so that exits: status $st: $(cat "$tmp/err")"
# the same broken helix.so before the build tree's good one: the good one runs
S42_BADCTOR=crash "$S42" run "$tmp/helix.kp" --plugins "$tmp/hx" --dump >"$tmp/out" 2>"$tmp/err" && ok ||
  bad "a broken helix.so shadowed the good one: $(cat "$tmp/err")"
unset S42_MARKER

# A *.so that is no plugin file at all -- a FIFO, a directory, a symbolic
# link that loops or leads nowhere -- is listed as refused with what it is
# (never opened: a FIFO would wait for a writer), in `s42 plugins`, its
# --json and E-FUNC's notes; a symbolic link to a plugin file is one
mkdir -p "$tmp/odd/dir.so" "$tmp/oddhx"
mkfifo "$tmp/odd/fifo.so" "$tmp/oddhx/helix.so"
ln -s loop.so "$tmp/odd/loop.so"
ln -s nothere.so "$tmp/odd/dangling.so"
cp "$BUILD/test-plugins/good/good.so" "$tmp/good-real.so"
ln -s ../good-real.so "$tmp/odd/good.so"
timeout 20 "$S42" plugins --plugins "$tmp/odd" >"$tmp/out" 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && grep -qx "refused: $tmp/odd/fifo.so is a FIFO, not a plugin file" "$tmp/out" &&
  grep -qx "refused: $tmp/odd/dir.so is a directory" "$tmp/out" &&
  grep -qx "refused: $tmp/odd/loop.so is a symbolic link that loops" "$tmp/out" &&
  grep -qx "refused: $tmp/odd/dangling.so is a symbolic link to nothere.so, which does not exist" "$tmp/out" &&
  grep -qx "good 0.1 (ABI 1.1) $tmp/odd/good.so" "$tmp/out" && ok ||
  bad "s42 plugins beside a FIFO, a directory and links: status $st" "$(cat "$tmp/out" "$tmp/err")"
timeout 20 "$S42" plugins --json --plugins "$tmp/odd" >"$tmp/out" 2>"$tmp/err"
st=$?
if [ $st -eq 0 ] && python3 - "$tmp/out" "$tmp/odd" <<'PYEOF'
import json, sys
j = json.load(open(sys.argv[1]))
d = sys.argv[2]
want = {d + "/fifo.so": "is a FIFO, not a plugin file", d + "/dir.so": "is a directory",
        d + "/loop.so": "is a symbolic link that loops",
        d + "/dangling.so": "is a symbolic link to nothere.so, which does not exist"}
got = {r["path"]: r["reason"] for r in j["refused"]}
assert all(got.get(p) == r for p, r in want.items()), got
assert any(p["path"] == d + "/good.so" and p["name"] == "good" for p in j["plugins"]), j["plugins"]
PYEOF
then ok; else bad "s42 plugins --json beside a FIFO: status $st" "$(cat "$tmp/out" "$tmp/err")"; fi
printf '№1 G63 ^\n№2 M02 ^\n' > "$tmp/g63.kp"
timeout 20 "$S42" check "$tmp/g63.kp" --plugins "$tmp/odd" 2>"$tmp/err"
st=$?
[ $st -eq 1 ] && grep -q "error: N1: G63 is not a function of the 2С42 or of a plugin found \[E-FUNC\]" "$tmp/err" &&
  grep -qF "note: N1: the plugin file $tmp/odd/fifo.so is a FIFO, not a plugin file" "$tmp/err" &&
  grep -qF "note: N1: the plugin file $tmp/odd/dir.so is a directory" "$tmp/err" &&
  grep -qF "note: N1: the plugin file $tmp/odd/loop.so is a symbolic link that loops" "$tmp/err" && ok ||
  bad "E-FUNC's notes beside a FIFO: status $st" "$(cat "$tmp/err")"
printf '№1 M30 ^\n№2 M02 ^\n' > "$tmp/m30.kp"
timeout 20 "$S42" run "$tmp/m30.kp" --plugins "$tmp/odd" --dump >"$tmp/out" 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && grep -q '"r":\[0,1,' "$tmp/out" && ok || bad "good.so through a symbolic link: status $st: $(cat "$tmp/err")"
# helix.so a FIFO, and no other helix.so: G12 says what the file is
timeout 20 "$tmp/bin/s42" run "$tmp/helix.kp" --plugins "$tmp/oddhx" >/dev/null 2>"$tmp/err"
st=$?
[ $st -eq 1 ] && grep -qF "G12 (helical interpolation) needs the helix plugin: $tmp/oddhx/helix.so is a FIFO, not a plugin file [E-PLUGIN]" "$tmp/err" &&
  ok || bad "helix.so a FIFO: status $st: $(cat "$tmp/err")"

# A plugin that passes the probe and then crashes in a callback (cbcrash:
# a null write, a division by zero, abort(), a stack overflow, in run(),
# check(), advance() or describe()): the crash guard catches the signal,
# the block fails with E-PLUGIN naming the plugin, the signal and the
# callback, and the run ends as on any error: status 1, the dump
cc_dir="$BUILD/test-plugins/cbcrash"
for c in "G54 2 SIGSEGV run" "G55 2 SIGFPE run" "G56 2 SIGABRT run" "G57 2 SIGSEGV run" "G58 2 SIGSEGV check" \
         "G59 3 SIGSEGV advance" "G60 2 SIGSEGV describe"; do
  set -- $c
  g=$1 n=$2 sig=$3 cb=$4
  t_case "$g"
  printf '№1 G01 X+10 F100 ^\n№2 %s ^\n№3 G01 X+10 F100 ^\n№4 M02 ^\n' "$g" > "$tmp/crash.kp"
  "$S42" run "$tmp/crash.kp" --plugins "$cc_dir" --dump >"$tmp/out" 2>"$tmp/err"
  st=$?
  msg="the cbcrash plugin crashed ($sig) in $cb(): it is not called again"
  [ $st -eq 1 ] && grep -qF "crash.kp:$n:1: error: N$n: $msg [E-PLUGIN]" "$tmp/err" &&
    grep -qF "{\"status\":\"error\",\"error\":{\"code\":\"E-PLUGIN\",\"n\":$n,\"line\":$n,\"col\":1,\"message\":\"$msg\"" "$tmp/out" &&
    ok || bad "status $st" "$(cat "$tmp/err")" "$(head -c 300 "$tmp/out")"
done
t_case ""
# a crash in fini(), as s42 exits, changes nothing of the run
printf '№1 G61 ^\n№2 M02 ^\n' > "$tmp/fini.kp"
"$S42" run "$tmp/fini.kp" --plugins "$cc_dir" --dump >"$tmp/out" 2>"$tmp/err"
st=$?
[ $st -eq 0 ] && grep -q '"status":"end"' "$tmp/out" && ok || bad "a crash in fini: status $st: $(cat "$tmp/err")"
# s42 tui: the run ends with the error on the message line, Пуск again is
# refused with the same words (the plugin is not called again), and the
# terminal quits as always, with the tty as it was
if t_have tmux; then
  . "$(dirname "$0")/../tmux.sh"
  tm_init "$tmp"
  printf '№1 G01 X+10 F100 ^\n№2 G54 ^\n№3 M02 ^\n' > "$tmp/crash.kp"
  tm_run tui 100 30 "$tmp" -e LC_ALL=C.UTF-8 -e TERM=screen "$(cd "$(dirname "$S42")" && pwd)/$(basename "$S42")" tui \
    crash.kp --plugins "$(cd "$cc_dir" && pwd)"
  msg="2:1 error N2: the cbcrash plugin crashed (SIGSEGV) in run(): it is not called again [E-PLUGIN]"
  if tm_wait tui -F "Пуск (F5 or" 10; then
    tm_keys tui g
    tm_wait tui -F "$msg" 10 && ok || bad "s42 tui: no crash message" "$(tm_pane tui)"
    tm_keys tui g
    tm_wait tui -F "Пуск: the cycle starts" 10 && tm_wait tui -F "$msg" 10 && ok ||
      bad "s42 tui, Пуск again" "$(tm_pane tui)"
    tm_keys tui q
    if tm_ended tui 10; then
      [ "$TM_STATUS" = "exit=0" ] && tm_stty_same && ok || bad "s42 tui after a crash quit with $TM_STATUS"
    else
      bad "s42 tui did not quit after a plugin crashed" "$(tm_pane tui)"
    fi
  else
    bad "s42 tui did not start" "$(tm_pane tui)"
  fi
  tm_kill tui
  tm_end
else
  echo "plugins: tmux is not installed: s42 tui on a crashing plugin was skipped"
fi

t_done
