#!/bin/sh
# The dialect seam (issue 16): the registry of the s42 users get, and a test
# s42 built with the fixture dialect (tests/dialect/fixture) added the way a
# dialect's folder adds itself.   usage: run.sh S42 FIXTURE_S42
S42=$1
FIX=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL dialect: $*"; fail=$((fail + 1)); }
# expect WHAT STATUS WANT-IN-OUTPUT COMMAND...: the status and a line of its stdout+stderr
expect() {
  what=$1 want=$2 text=$3
  shift 3
  "$@" >"$T/out" 2>&1
  st=$?
  if [ "$st" -eq "$want" ] && { [ -z "$text" ] || grep -qF -- "$text" "$T/out"; }; then ok; else
    bad "$what: status $st (expected $want), output: $(head -c 400 "$T/out")"
  fi
}

printf '; count to 20 by 2\nN10 R1 = 5\nN20 R1 + 2\nN30 IF R1 < 20 GOTO N20\nN40 END\n' >"$T/count.fix"
printf 'N10 R1 = 9999999\nN20 R1 + 1\nN30 END\n' >"$T/over.fix"
printf 'N10 R1 = 5\nN20 R12 + 2\nN30 IF R1 ~ 20 GOTO N20\nN40 IF R1 < 3 GOTO N77\nN50 END\n' >"$T/bad.fix"

# the s42 users get: the 2С42 and the 2У22; the fixture is not in it
expect "s42 dialects" 0 "2c42       .kp    grinder" "$S42" dialects
if "$S42" dialects | grep -q fixture; then bad "the product lists the fixture"; else ok; fi
expect "unknown --dialect" 2 "no dialect 'fixture' (2c42, 2u22)" "$S42" run --dialect fixture "$T/count.fix"
expect "--dialect 2c42 on any extension" 0 "" "$S42" check --dialect 2c42 programs/drill_point.kp
cp programs/drill_point.kp "$T/drill.txt"
expect "an unknown extension is the 2С42's" 0 '"status":"end"' "$S42" run "$T/drill.txt" --dump

# the test s42: the fixture registered beside the 2С42
expect "fixture listed" 0 "fixture    .fix   none" "$FIX" dialects
expect "the 2С42 still runs" 0 '"status":"end"' "$FIX" run programs/drill_point.kp --dump --plugins build/plugins
expect "by extension" 0 '"blocks":[10,20,30,20,30,20,30,20,30,20,30,20,30,20,30,20,30,40],"time":0,"pos":{},"r":{"1":21}}' \
  "$FIX" run "$T/count.fix" --dump
cp "$T/count.fix" "$T/count.txt"
expect "by --dialect" 0 '"r":{"1":21}' "$FIX" run --dialect fixture "$T/count.txt" --dump
expect "--dialect=NAME" 0 '"r":{"1":21}' "$FIX" run "$T/count.txt" --dialect=fixture --dump
expect "did you mean" 2 "no dialect 'fixtur': did you mean fixture? (2c42, 2u22, fixture)" "$FIX" check --dialect fixtur "$T/count.fix"
expect "check" 0 "" "$FIX" check "$T/count.fix"
expect "disasm" 0 "0002  SETP    r1" "$FIX" disasm "$T/count.fix"
expect "trace" 0 '{"seq":18,"n":40,"line":5,"depth":0,"motion":"none","pos":{},"feed":0,"t":0}' "$FIX" run "$T/count.fix" --trace=json
expect "errors: file, line, column, block" 1 "bad.fix:2:5: error: N20: registers are R0..R9 [E-RANGE]" "$FIX" check "$T/bad.fix"
expect "a second error on its line" 1 "bad.fix:3:11: error: N30: expected a relation: < = > [E-SYNTAX]" "$FIX" check "$T/bad.fix"
expect "a jump to nowhere" 1 "bad.fix:4:14: error: N40: no block N77 to go to [E-TARGET]" "$FIX" check "$T/bad.fix"
expect "a run-time error" 1 '"error":{"code":"E-RANGE","n":20,"line":2' "$FIX" run "$T/over.fix" --dump
expect "its diagnostic" 1 "over.fix:2:5: error: N20:" "$FIX" run "$T/over.fix"
expect "the block budget" 1 '"code":"E-LIMIT"' "$FIX" run "$T/count.fix" --max-blocks 5 --dump
expect "no panel" 2 "the fixture dialect has no panel yet" "$FIX" tui "$T/count.fix"
expect "no machine for a plot" 2 "need a machine" "$FIX" plot "$T/count.fix" -o "$T/x.png"
echo "dialect: $pass passed, $fail failed"
[ $fail -eq 0 ]
