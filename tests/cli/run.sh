#!/bin/sh
# The command line's own promises (contracts.md sec. 1): output that cannot
# be written is status 4 with the reason, for every command that writes;
# a CR-only program reads as lines.   usage: run.sh S42
S42=${1:-./s42}
. "$(dirname "$0")/../lib.sh"
t_init cli

# stdout on a full disk: every command that prints exits 4 and says why
if [ -w /dev/full ]; then
  for args in "--help" "--version" "disasm programs/drill_point.kp" "plugins" \
              "run programs/drill_point.kp --dump" "run programs/drill_point.kp --trace" \
              "run programs/drill_point.kp --screen"; do
    # shellcheck disable=SC2086
    "$S42" $args >/dev/full 2>"$T/err"
    st=$?
    if [ "$st" -ne 4 ]; then
      bad "s42 $args >/dev/full: status $st, expected 4"
    elif ! grep -q 'error writing the output' "$T/err"; then
      bad "s42 $args >/dev/full: no message on stderr"
    else
      ok
    fi
  done
  # check prints nothing on stdout: a full stdout is no error
  if "$S42" check programs/drill_point.kp >/dev/full 2>"$T/err"; then ok; else bad "check >/dev/full failed"; fi
else
  echo "cli: /dev/full is not here: the full-disk cases were skipped"
fi

# out of memory while the program is read: one error, status 4, no crash
if [ -n "$ASAN_OPTIONS" ] || ldd "$S42" 2>/dev/null | grep -q libasan; then
  echo "cli: a sanitizer build: the out-of-memory shim cannot come before its malloc, that case was skipped"
elif cc -shared -fPIC -o "$T/oomshim.so" "$(dirname "$0")/oomshim.c" -ldl 2>/dev/null; then
  LD_PRELOAD="$T/oomshim.so" "$S42" check programs/drill_point.kp 2>"$T/err"
  st=$?
  if [ "$st" -eq 4 ] && [ "$(grep -c 'error:' "$T/err")" -eq 1 ] && grep -q 'out of memory: the program could not be read' "$T/err"; then
    ok
  else
    bad "out of memory: status $st, $(head -3 "$T/err")"
  fi
else
  echo "cli: no C compiler for the out-of-memory shim: that case was skipped"
fi

# CR-only line ends (an old Mac OS file): lines, comments and errors as with LF
printf '; a comment\r№1 G01 X+1000 F100 ^\r№2 G01 Q ^\r№3 M02 ^\r' >"$T/cr.kp"
"$S42" check "$T/cr.kp" 2>"$T/err"
st=$?
if [ "$st" -eq 1 ] && grep -q "cr.kp:3:8: error: N2: unexpected 'Q'" "$T/err" && grep -q 'CR alone' "$T/err"; then
  ok
else
  bad "CR-only file: status $st, $(cat "$T/err")"
fi
printf '; a comment\r№1 G01 X+1000 F100 ^\r№2 M02 ^\r' >"$T/cr2.kp"
if "$S42" run "$T/cr2.kp" --dump 2>/dev/null | grep -q '"status":"end"'; then ok; else bad "CR-only file does not run"; fi

# the source line and a caret under the column
printf '№1 G01 X+1000 F100 ^\n№2 G02 G17 I+1 Z+5 ^\n№3 M02 ^\n' >"$T/caret.kp"
"$S42" check "$T/caret.kp" 2>"$T/err"
printf '%s\n' "$T/caret.kp:2:16: error: N2: Z is not in the G17 plane of this arc (XY) [E-PLANE]" \
  '    2 | №2 G02 G17 I+1 Z+5 ^' '      |                ^' >"$T/want"
if cmp -s "$T/err" "$T/want"; then ok; else bad "caret: $(diff "$T/want" "$T/err")"; fi
# a long line: a window round the column; a control character as ?
python3 -c "
import sys
sys.stdout.write('№1 R1+' + '1+' * 200 + 'Q ^\n№2 M02 ^\n')" >"$T/long.kp"
"$S42" check "$T/long.kp" 2>"$T/err"
if sed -n 5p "$T/err" | grep -q '^    1 | \.\.\.1+1+1.*+1+Q \^$' && [ "$(sed -n 6p "$T/err" | tr -d ' |' )" = "^" ] &&
   [ "$(sed -n 5p "$T/err" | awk '{ print index($0, "Q") }')" = "$(sed -n 6p "$T/err" | awk '{ print index($0, "^") }')" ] &&
   [ "$(sed -n 2p "$T/err" | wc -c)" -lt 120 ]; then
  ok
else
  bad "long line: $(cat "$T/err")"
fi
printf '№1 R1+1 \001 ^\n№2 M02 ^\n' >"$T/ctl.kp"
"$S42" check "$T/ctl.kp" 2>"$T/err"
if sed -n 2p "$T/err" | grep -q '^    1 | №1 R1+1 ? \^$'; then ok; else bad "control character: $(cat "$T/err")"; fi

# colour on a terminal only, and never with NO_COLOR (script gives a pty)
if command -v script >/dev/null 2>&1; then
  script -qec "$S42 check $T/caret.kp" /dev/null >"$T/tty" 2>&1
  if grep -q "$(printf '\033')\[1;31merror" "$T/tty"; then ok; else bad "no colour on a terminal: $(cat -v "$T/tty")"; fi
  NO_COLOR=1 script -qec "$S42 check $T/caret.kp" /dev/null >"$T/tty" 2>&1
  if grep -q "$(printf '\033')" "$T/tty"; then bad "colour despite NO_COLOR"; else ok; fi
  TERM=dumb script -qec "$S42 check $T/caret.kp" /dev/null >"$T/tty" 2>&1
  if grep -q "$(printf '\033')" "$T/tty"; then bad "colour on TERM=dumb"; else ok; fi
  if grep -q "$(printf '\033')" "$T/err"; then bad "colour into a file"; else ok; fi
else
  echo "cli: script (util-linux) is not here: the colour cases were skipped"
fi

# check --json: one object a diagnostic; the status: 1 when a program has
# errors even when another file is missing, 4 when only a file is missing
"$S42" check --json "$T/caret.kp" "$T/missing.kp" programs/drill_point.kp >"$T/json" 2>"$T/err"
st=$?
if [ "$st" -eq 1 ] && python3 - "$T/json" "$T/caret.kp" "$T/missing.kp" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
assert len(rows) == 2, rows
a, b = rows
assert a == {"file": sys.argv[2], "line": 2, "col": 16, "block": 2, "severity": "error", "code": "E-PLANE",
             "message": "Z is not in the G17 plane of this arc (XY)"}, a
assert b["file"] == sys.argv[3] and b["severity"] == "error" and b["line"] is None, b
PY
then ok; else bad "check --json: status $st, $(cat "$T/json")"; fi
if grep -q 'missing.kp' "$T/err" && ! grep -q 'E-PLANE' "$T/err"; then ok; else bad "check --json stderr: $(cat "$T/err")"; fi
"$S42" check "$T/missing.kp" programs/drill_point.kp 2>/dev/null
st=$?; if [ "$st" -eq 4 ]; then ok; else bad "check of a missing file and a good one: status $st, expected 4"; fi
"$S42" check "$T/missing.kp" "$T/caret.kp" 2>/dev/null
st=$?; if [ "$st" -eq 1 ]; then ok; else bad "check of a missing file and a bad one: status $st, expected 1"; fi

# per-command help on stdout, status 0; "did you mean" for options and commands
if "$S42" run --help >"$T/out" 2>&1 && grep -q '^usage: s42 run' "$T/out" && grep -q -- '--operator FILE' "$T/out" &&
   ! grep -q -- '--json' "$T/out"; then ok; else bad "run --help: $(head -3 "$T/out")"; fi
if "$S42" help check >"$T/out" 2>&1 && grep -q -- '--json' "$T/out" && ! grep -q -- '--operator' "$T/out"; then ok; else bad "help check"; fi
"$S42" run programs/drill_point.kp --opertor x 2>"$T/err"
st=$?; if [ "$st" -eq 2 ] && grep -q "did you mean --operator?" "$T/err"; then ok; else bad "--opertor: $st $(cat "$T/err")"; fi
"$S42" tui --modbus-idel 3 2>"$T/err"
st=$?; if [ "$st" -eq 2 ] && grep -q "did you mean --modbus-idle?" "$T/err"; then ok; else bad "--modbus-idel: $(cat "$T/err")"; fi
"$S42" rnu x.kp 2>"$T/err"
st=$?; if [ "$st" -eq 2 ] && grep -q "did you mean run?" "$T/err"; then ok; else bad "rnu: $(cat "$T/err")"; fi
"$S42" run programs/drill_point.kp --zzzzzz 2>"$T/err"
if grep -q "did you mean" "$T/err"; then bad "a far option got a suggestion: $(cat "$T/err")"; else ok; fi

# bash completion: options from the command's --help, .kp files
if command -v bash >/dev/null 2>&1; then
  got=$(S42="$S42" bash -c '. scripts/s42.bash; COMP_WORDS=("$S42" run --oper); COMP_CWORD=2; _s42; echo "${COMPREPLY[*]}"')
  if [ "$got" = "--operator" ]; then ok; else bad "completion of run --oper: '$got'"; fi
  got=$(S42="$S42" bash -c '. scripts/s42.bash; COMP_WORDS=("$S42" plu); COMP_CWORD=1; _s42; echo "${COMPREPLY[*]}"')
  if [ "$got" = "plugins" ]; then ok; else bad "completion of plu: '$got'"; fi
fi

# plugins --json: one object that parses, with the plugins found
if "$S42" plugins --json >"$T/out" && python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
names = sorted(p["name"] for p in d["plugins"])
assert d["abi"] and isinstance(d["searched"], list) and isinstance(d["refused"], list)
assert {"helix", "oscillation"} <= set(names), names
assert all(f["function"][0] in "GM" for p in d["plugins"] for f in p["functions"])
' "$T/out"; then ok; else bad "plugins --json: $(head -c 300 "$T/out")"; fi

t_done
