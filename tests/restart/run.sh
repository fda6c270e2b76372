#!/bin/sh
# Kill `s42 run` with SIGKILL at many points of a long cycle with M15 and
# restart it: every restart must either continue from a consistent state
# (and end with the right sum) or refuse cleanly with E-STATE -- never use a
# half-written state.  Then damage the state file in several ways and check
# that the restart is refused; edit its fields by hand with the checksum
# recomputed (FORGE, tests/restart/forge.c) and check that each is refused,
# naming the field, with status 1 and a dump that is valid JSON.
#   sh tests/restart/run.sh S42 FORGE
s42=$1
forge=${2:-build/tests/restart/forge}
prog=tests/restart/loop.kp
want=2001000
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
st="$tmp/loop.state"
pass=0; fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL restart: $*"; }
r2() { python3 -c 'import json,sys; d=json.loads(sys.stdin.readline()); print(d["status"], int(d["r"][2]) if d["status"]=="end" else (d["error"] or {}).get("code"))'; }

i=0
for delay in 0 0.01 0.03 0.05 0.08 0.1 0.15 0.2 0.3 0.4 0.5 0.6 0.8 1.0; do
  i=$((i + 1))
  rm -f "$st"
  "$s42" run "$prog" --state "$st" >/dev/null 2>&1 &
  pid=$!
  sleep "$delay"
  kill -9 "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  out=$("$s42" run "$prog" --restart --state "$st" --dump 2>/dev/null | r2)
  if [ -f "$st" ] || [ "$out" != "error E-STATE" ]; then
    case "$out" in
      "end $want") ok ;;
      "error E-STATE") [ -f "$st" ] && bad "kill after ${delay}s: a state file exists but the restart was refused" || ok ;;
      *) bad "kill after ${delay}s: restart gave '$out', want 'end $want'" ;;
    esac
  else
    ok
  fi
  # a killed write leaves only its temporary file, which the next save
  # (the restart's, when it ran) removed
  if [ "$out" = "end $want" ] && ls "$tmp"/loop.state.tmp* >/dev/null 2>&1; then
    bad "kill after ${delay}s: the restart's saves left $(ls "$tmp"/loop.state.tmp*)"
  fi
done

# a good state, then damaged copies
"$s42" run "$prog" --state "$st" --max-blocks 3000 >/dev/null 2>&1
cp "$st" "$tmp/good"
check_refused() {
  out=$("$s42" run "$prog" --restart --state "$1" --dump 2>/dev/null | r2)
  [ "$out" = "error E-STATE" ] && ok || bad "$2: restart gave '$out', want a refusal"
}
head -c 100 "$tmp/good" > "$tmp/short"; check_refused "$tmp/short" "truncated state"
cp "$tmp/good" "$tmp/flip"
python3 -c "import sys; b=bytearray(open(sys.argv[1],'rb').read()); b[len(b)//2]^=1; open(sys.argv[1],'wb').write(b)" "$tmp/flip"
check_refused "$tmp/flip" "a flipped bit"
: > "$tmp/empty"; check_refused "$tmp/empty" "an empty file"
check_refused "$tmp/missing" "a missing file"
cat "$tmp/good" > "$tmp/long"; printf x >> "$tmp/long"; check_refused "$tmp/long" "trailing bytes"
sed 's/2000)3/2001)3/' "$prog" > "$tmp/changed.kp"
out=$("$s42" run "$tmp/changed.kp" --restart --state "$tmp/good" --dump 2>/dev/null | r2)
[ "$out" = "error E-STATE" ] && ok || bad "changed program text: restart gave '$out'"
out=$("$s42" run "$prog" --restart --state "$tmp/good" --dump 2>/dev/null | r2)
[ "$out" = "end $want" ] && ok || bad "good state: restart gave '$out'"

# the temporary file a killed save left is removed by the next save; a file
# that only looks like one is not
printf 'half a state' > "$st.tmpAbC123"
printf 'mine' > "$st.tmpAbC12"
"$s42" run "$prog" --state "$st" --max-blocks 10 >/dev/null 2>&1
[ ! -e "$st.tmpAbC123" ] && [ -e "$st.tmpAbC12" ] && ok || bad "a stale $st.tmpAbC123 was not removed (or another file was)"
rm -f "$st.tmpAbC12"

# --state never replaces what is not a restart state: the run stops at the
# first M15 with E-STATE (status 4, the dump says so), the file intact
cp "$prog" "$tmp/self.kp"
"$s42" run "$tmp/self.kp" --state "$tmp/self.kp" --dump > "$tmp/out" 2> "$tmp/err"
st4=$?
got=$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); e=d["error"] or {}; print(d["status"], e.get("code"), e.get("n"))' "$tmp/out")
if [ "$st4" = 4 ] && [ "$got" = "error E-STATE 3" ] && cmp -s "$prog" "$tmp/self.kp" &&
   grep -q "self.kp:5:1: error: N3: cannot save the M15 restart state: .*self.kp is not an s42 restart state: it is not replaced" "$tmp/err"; then
  ok
else
  bad "--state naming the program: status $st4, dump '$got', $(cat "$tmp/err")"
fi
# a save that fails (no such directory): E-STATE in the dump, status 4; the
# same under --modbus (an operator script starts the cycle without a client)
"$s42" run "$prog" --state "$tmp/no/such/dir.state" --dump > "$tmp/out" 2> "$tmp/err"
st4=$?
got=$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d["status"], (d["error"] or {}).get("code"))' "$tmp/out")
[ "$st4" = 4 ] && [ "$got" = "error E-STATE" ] && ok || bad "a failed save: status $st4, dump '$got'"
printf 'key PUSK\n' > "$tmp/go.op"
timeout 20 "$s42" run "$prog" --modbus 127.0.0.1:0 --operator "$tmp/go.op" --state "$tmp/no/such/dir.state" --dump \
  > "$tmp/out" 2> "$tmp/err"
st4=$?
got=$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d["status"], (d["error"] or {}).get("code"))' "$tmp/out")
[ "$st4" = 4 ] && [ "$got" = "error E-STATE" ] && grep -q "error: N3: cannot save the M15 restart state" "$tmp/err" && ok ||
  bad "a failed save under --modbus: status $st4, dump '$got', $(cat "$tmp/err")"

# hand-edited states with a correct checksum: each field refused by name
sub=tests/restart/sub.kp
"$s42" run "$sub" --state "$tmp/sub.state" --max-blocks 6 >/dev/null 2>&1
"$s42" run tests/restart/osc.kp --state "$tmp/osc.state" >/dev/null 2>&1
# forged PROGRAM STATE PATTERN FIELD VALUE ...: edit a copy, restart from it;
# stderr must say "restart refused: PATTERN"
forged() {
  prog=$1 from=$2 pat=$3
  shift 3
  cp "$from" "$tmp/forged"
  if ! "$forge" "$tmp/forged" "$@"; then
    bad "forge $*"
    return
  fi
  "$s42" run "$prog" --restart --state "$tmp/forged" --dump > "$tmp/out" 2> "$tmp/err"
  st=$?
  got=$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d["status"], (d["error"] or {}).get("code"))' \
        "$tmp/out" 2>&1)
  if [ "$st" != 1 ] || [ "$got" != "error E-STATE" ]; then
    bad "$*: status $st, dump '$got', want 1 and a refusal"
  elif ! grep -q "restart refused: $pat.*\[E-STATE\]" "$tmp/err"; then
    bad "$*: stderr does not say '$pat': $(cat "$tmp/err")"
  else
    ok
  fi
}
# field PATTERN FIELD VALUE ...: a field of sub.kp's state, named in the refusal
field() {
  pat=$1
  shift
  forged "$sub" "$tmp/sub.state" "the state's $pat" "$@"
}
field 'array 1 pointer is -3, not 0-15' arr.1.ptr -3
field 'array 2 pointer is 16, not 0-15' arr.2.ptr 16
field 'array 1 length is -1, not 0-15' arr.1.len -1
field 'array 1 cell 0 is nan' arr.1.cell.0 nan
field 'array 2 cell 3 is 7, past the array.s length 0' arr.2.cell.3 7
field 'R5 is 100000000, not -9999999..9999999' r.5 1e8
field 'R113 is -inf' r.113 -inf
field 'D1 is 400001, not 0..400000' r.114 400001
field 'TK is nan' r.115 nan
field 'UG is 1e+300' r.116 1e300
field 'F is 6001, not 0..6000' r.117 6001
field 'unused register 127 is 1' r.127 1
field 'time is nan, not 0..1e+15' t nan
field 'time is -5' t -5
field 'X position is 9223372036854775807 discretes' pos.X 9223372036854775807
field 'Y position is -9223372036854775808 discretes' pos.Y -9223372036854775808
field 'wheel state is 7, not 0-2' wheel 7
field 'feed override is 200, not 0-150' override 200
field 'M25/M26 override switch is 5' override_allowed 5
field 'M22/M23 correction switch is 2' corr_allowed 2
field 'count of executed blocks is 9007199254740993' blocks 9007199254740993
field 'restart block is index 40' block 40
field 'restart block (line 5, N11) has no M15' block 1
field 'code address is 3, not' pc 3
field 'sub call depth is 9, not 0-8' depth 9
field 'sub call depth is -2' depth -2
field 'restart block N10 is not in the main program' depth 0
field 'sub call 1 returns to code address 2' frame.1.ret 2
field 'sub call 1 returns to code address 4000000000' frame.1.ret 4000000000
field 'sub call 1 is made from block index 1' frame.1.block 1
field 'sub call 1 repeats left is 99999' frame.1.left 99999
field 'sub call 1 saved F is -1' frame.1.saved -1
field 'sub call 1 jump condition is 9' frame.1.jflag 9
field 'plugin count is 100' nplug 100
field 'plugin 1.s name is empty' nplug 1
field 'oscillation plugin.s record is 600 bytes' nplug 1 plug.1.name oscillation plug.1.len 600
field 'P3 display switch is -1' p3 -1
field 'G29 line count is 20' np3 20
field 'G29 line 1 parameter is 500' p3l.1.reg 500
field 'G29 line 1 holds U+FFFFFFFF' p3l.1.ch.2 0xffffffff
field 'directive is text 99999' directive 99999
field 'directive text is not that of its M18' dirtext 'ВСЕ ГАРАЗД'
field 'directive text is not UTF-8' directive 0 dirtext "$(printf 'A\377B')"
# the oscillation plugin's record: its own checks (defined 2, axis 9)
forged tests/restart/osc.kp "$tmp/osc.state" 'the oscillation plugin cannot take back its saved state' plug.1.byte.0 2
forged tests/restart/osc.kp "$tmp/osc.state" 'the oscillation plugin cannot take back its saved state' plug.1.byte.8 9
# the unedited copies still restart (forge itself changes nothing else)
cp "$tmp/sub.state" "$tmp/same"; "$forge" "$tmp/same" wheel 0
out=$("$s42" run "$sub" --restart --state "$tmp/same" --dump 2>/dev/null | python3 -c 'import json,sys; d=json.load(sys.stdin); print(d["status"], d["r"][100])')
[ "$out" = "end 3" ] && ok || bad "an unedited forged copy: restart gave '$out'"

echo "restart: $pass passed, $fail failed"
[ "$fail" = 0 ]
