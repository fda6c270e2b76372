#!/bin/sh
# The command line's own promises (contracts.md sec. 1): output that cannot
# be written is status 4 with the reason, for every command that writes;
# a CR-only program reads as lines.   usage: run.sh S42
S42=${1:-./s42}
T=${TMPDIR:-/tmp}/s42-cli.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL cli $1"; fail=$((fail + 1)); }

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

echo "cli: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
