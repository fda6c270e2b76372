#!/bin/sh
# What s42 maps: `s42 run` none of the libraries only some commands need
# (ncursesw and libtinfo for s42 tui, libmodbus for --modbus, cairo for a
# plot, OpenCV for a tooth search); those commands load theirs with dlopen
# when they start (src/host/curses_dl.c, modbus_dl.c, cairo_dl.c; the
# toothsearch plugin's imgcodecs: tests/plugins/run.sh).  LD_DEBUG=files
# lists every object the dynamic loader maps.  Then each library missing
# (a mount namespace of our own puts /dev/null over its file; skipped
# where unshare cannot make one): the command that needs it fails naming
# it, s42 run does not notice.
# usage: tests/load/run.sh S42
S42=$1
. "$(dirname "$0")/../lib.sh"
t_init load
tmp=$T
case $S42 in /*) s42=$S42 ;; *) s42=$(pwd)/$S42 ;; esac

printf '№1 R1+1 ^\n№2 G01 X+1000 F1000 ^\n№3 M02 ^\n' > "$tmp/two.kp"
mapped() {   # the objects mapped, one a line
  grep -o 'file=[^ ]*' "$1" | sed 's/^file=//' | sort -u
}

# s42 run, check and disasm: none of them, and nothing loaded later
for cmd in run check disasm; do
  t_case "s42 $cmd"
  LD_DEBUG=files "$s42" $cmd "$tmp/two.kp" >/dev/null 2>"$tmp/ld"
  st=$?
  [ $st -eq 0 ] && ok || bad "status $st: $(grep -v '^ *[0-9]*:' "$tmp/ld" | head -3)"
  mapped "$tmp/ld" >"$tmp/libs"
  grep -q '^libc\.so' "$tmp/libs" && ok || bad "LD_DEBUG=files shows no libc (the checks below prove nothing)"
  if grep -E 'ncurses|tinfo|modbus|cairo|opencv' "$tmp/libs" >"$tmp/extra"; then
    bad "mapped what it does not use: $(tr '\n' ' ' <"$tmp/extra")"
  else
    ok
  fi
  # and nothing with dlopen (a sanitizer's runtime may be linked: the
  # libraries s42 is linked with are checked below)
  if grep 'dynamically loaded by' "$tmp/ld" >"$tmp/other"; then
    bad "loaded with dlopen: $(mapped "$tmp/other" | tr '\n' ' ')"
  else
    ok
  fi
done
t_case ""
# nor does the binary name them
if t_have readelf; then
  readelf -d "$s42" >"$tmp/dyn" 2>&1
  if grep NEEDED "$tmp/dyn" | grep -E 'ncurses|tinfo|modbus|cairo' >"$tmp/needed"; then
    bad "s42 is linked with $(sed 's/.*\[\(.*\)\].*/\1/' "$tmp/needed" | tr '\n' ' ')"
  else
    ok
  fi
fi

# s42 tui loads ncursesw (and libtinfo) when it starts, before it finds no
# terminal; with --modbus the server's libmodbus too (port 0: any free one)
LD_DEBUG=files "$s42" tui --modbus=127.0.0.1:0 "$tmp/two.kp" </dev/null >/dev/null 2>"$tmp/ld"
st=$?
[ $st -eq 2 ] && ok || bad "s42 tui without a terminal: status $st, want 2: $(grep -v '^ *[0-9]*:' "$tmp/ld" | head -3)"
mapped "$tmp/ld" >"$tmp/libs"
for l in libncursesw libtinfo libmodbus; do
  grep -q "^$l\.so" "$tmp/libs" && ok || bad "s42 tui --modbus did not load $l"
done
LD_DEBUG=libs "$s42" tui --modbus=127.0.0.1:0 "$tmp/two.kp" </dev/null >/dev/null 2>"$tmp/ldl"
curses=$(sed -n 's/.*calling init: \(.*libncursesw\.so[.0-9]*\)$/\1/p' "$tmp/ldl" | head -n 1)
modbus=$(sed -n 's/.*calling init: \(.*libmodbus\.so[.0-9]*\)$/\1/p' "$tmp/ldl" | head -n 1)

# each library missing in turn (its file /dev/null: "file too short")
if [ -n "$curses" ] && [ -n "$modbus" ] &&
   unshare -rm sh -c "mount --bind /dev/null '$curses'" 2>/dev/null; then
  hide() {   # hide FILE CMD...: run CMD with FILE unusable
    f=$1
    shift
    unshare -rm sh -c 'mount --bind /dev/null "$0" && exec "$@"' "$f" "$@"
  }
  t_case "no ncursesw"
  hide "$curses" "$s42" run "$tmp/two.kp" --dump >"$tmp/out" 2>"$tmp/err"
  st=$?
  [ $st -eq 0 ] && grep -q '"status":"end"' "$tmp/out" && ok || bad "s42 run: status $st: $(cat "$tmp/err")"
  hide "$curses" "$s42" tui "$tmp/two.kp" </dev/null >/dev/null 2>"$tmp/err"
  st=$?
  [ $st -eq 4 ] && ok || bad "s42 tui: status $st, want 4"
  grep -q "^s42 tui: cannot load libncursesw\.so\.[0-9]* (the terminal draws with ncursesw): " "$tmp/err" && ok ||
    bad "s42 tui does not name the library: $(cat "$tmp/err")"
  t_case "no libmodbus"
  hide "$modbus" "$s42" run "$tmp/two.kp" --dump >"$tmp/out" 2>"$tmp/err"
  st=$?
  [ $st -eq 0 ] && grep -q '"status":"end"' "$tmp/out" && ok || bad "s42 run: status $st: $(cat "$tmp/err")"
  hide "$modbus" "$s42" run "$tmp/two.kp" --modbus=127.0.0.1:0 >/dev/null 2>"$tmp/err"
  st=$?
  [ $st -eq 4 ] && ok || bad "s42 run --modbus: status $st, want 4"
  grep -q "^s42: --modbus: cannot load libmodbus\.so\.[0-9]* (the Modbus server needs libmodbus): " "$tmp/err" && ok ||
    bad "s42 run --modbus does not name the library: $(cat "$tmp/err")"
  hide "$modbus" "$s42" tui --modbus=127.0.0.1:0 "$tmp/two.kp" </dev/null >/dev/null 2>"$tmp/err"
  st=$?
  [ $st -eq 4 ] && grep -q "cannot load libmodbus" "$tmp/err" && ok ||
    bad "s42 tui --modbus: status $st: $(cat "$tmp/err")"
  t_case ""
else
  echo "load: no mount namespace here (unshare -rm): the missing-library checks were skipped"
fi

t_done
