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
killsave=${3:-build/tests/restart/killsave.so}
prog=tests/restart/loop.kp
want=2001000
. "$(dirname "$0")/../lib.sh"
t_init restart
# The kill passes and the rest run on a tmpfs: a save's fsyncs cost nothing
# there (on a busy disk this test's 56,000 fsyncs once took 287 s), and a
# SIGKILL does not need them: the kernel keeps what was written either way
# (they are for a power cut).  One pass runs on the real disk ($T).
t_fast_dir
disk=$T
tmp=$T_FAST
echo "restart: the kill passes in $tmp ($(stat -f -c %T "$tmp")), one in $disk ($(stat -f -c %T "$disk"))"
st="$tmp/loop.state"
r2() { python3 -c 'import json,sys; d=json.loads(sys.stdin.readline()); print(d["status"], int(d["r"][2]) if d["status"]=="end" else (d["error"] or {}).get("code"))'; }
# secs MS K N: K/N of MS milliseconds, in seconds for sleep
secs() { awk -v ms="$1" -v k="$2" -v n="$3" 'BEGIN { printf "%.3f", ms * k / n / 1000 }'; }

# killpass PROGRAM STATE DELAY SUM: run, SIGKILL after DELAY seconds, restart:
# the restart ends with SUM, or is refused when no state was saved yet
killpass() {
  kp=$1 sf=$2 delay=$3 sum=$4
  rm -f "$sf" "$sf".tmp*
  "$s42" run "$kp" --state "$sf" >/dev/null 2>&1 &
  pid=$!
  sleep "$delay"
  kill -9 "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  out=$("$s42" run "$kp" --restart --state "$sf" --dump 2>/dev/null | r2)
  if [ -f "$sf" ] || [ "$out" != "error E-STATE" ]; then
    case "$out" in
      "end $sum") ok ;;
      "error E-STATE") [ -f "$sf" ] && bad "kill after ${delay}s: a state file exists but the restart was refused" || ok ;;
      *) bad "kill after ${delay}s: restart gave '$out', want 'end $sum'" ;;
    esac
  else
    ok
  fi
  # a killed write leaves only its temporary file, which the next save
  # (the restart's, when it ran) removed
  if [ "$out" = "end $sum" ] && ls "$sf".tmp* >/dev/null 2>&1; then
    bad "kill after ${delay}s: the restart's saves left $(ls "$sf".tmp*)"
  fi
}

# 14 kills spread over the time an uninterrupted run takes here (0 % to
# 93 %: before the first save, between saves, inside one)
a=$(t_ms); "$s42" run "$prog" --state "$st" >/dev/null 2>&1; b=$(t_ms)
full=$((b - a))
k=0
while [ $k -lt 14 ]; do
  killpass "$prog" "$st" "$(secs $full $k 15)" $want
  k=$((k + 1))
done
# on the real disk, with fsyncs: a 200-pass loop killed half-way
sed 's/2000)3/200)3/' "$prog" > "$disk/loop200.kp"
a=$(t_ms); "$s42" run "$disk/loop200.kp" --state "$disk/loop.state" >/dev/null 2>&1; b=$(t_ms)
killpass "$disk/loop200.kp" "$disk/loop.state" "$(secs $((b - a)) 1 2)" 20100

# A kill that lands inside a save, every time: tests/restart/killsave.so
# (LD_PRELOAD) raises SIGKILL in the Nth save's write of its temporary file,
# after half of that write, or just before its rename.  The state file is
# then the previous save's, byte for byte, and the restart goes on from it.
# (Under make asan the shim is not first in the library list: allowed.)
ks() {   # ks DIR SPEC: loop.kp under the shim; KST its status, $1/log what the shim did
  rm -rf "$1"
  mkdir -p "$1"
  S42_KILLSAVE=$2 S42_KILLSAVE_LOG="$1/log" LD_PRELOAD="$killsave" \
    ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0" \
    "$s42" run "$prog" --state "$1/s.state" >/dev/null 2>&1
  KST=$?
}
size() { wc -c < "$1" | tr -d ' '; }
n=5
ks "$tmp/ren" "$n:rename"                    # save 5 written whole, not renamed
ren_tmp=$(ls "$tmp"/ren/s.state.tmp* 2>/dev/null)
if [ "$KST" = 137 ] && grep -qx "killed save $n before the rename of $tmp/ren/s.state.tmp[A-Za-z0-9]\{6\}" "$tmp/ren/log" &&
   [ -f "$tmp/ren/s.state" ] && [ -f "$ren_tmp" ] && [ "$(size "$ren_tmp")" = "$(size "$tmp/ren/s.state")" ]; then
  ok
else
  bad "killsave $n:rename: status $KST, log '$(cat "$tmp/ren/log" 2>/dev/null)', files $(ls "$tmp/ren")"
fi
ks "$tmp/ren2" "$((n + 1)):rename"           # save 6 not renamed: the file is save 5
cmp -s "$tmp/ren2/s.state" "$ren_tmp" && ok ||
  bad "killsave: the state after save $n differs from save $n's temporary file (the saves are not deterministic?)"
for w in 1 2; do                             # write 1: the header; 2: the record
  ks "$tmp/w$w" "$n:write:$w"
  wt=$(ls "$tmp"/w$w/s.state.tmp* 2>/dev/null)
  if [ "$KST" = 137 ] && grep -qx "killed save $n in write $w: [0-9]* of [0-9]* bytes of $tmp/w$w/s.state.tmp[A-Za-z0-9]\{6\}" "$tmp/w$w/log" &&
     [ -f "$wt" ] && [ "$(size "$wt")" -lt "$(size "$ren_tmp")" ] && cmp -s -n "$(size "$wt")" "$wt" "$ren_tmp"; then
    ok                                       # half written: a prefix of the whole save
  else
    bad "killsave $n:write:$w: status $KST, log '$(cat "$tmp/w$w/log" 2>/dev/null)', files $(ls "$tmp/w$w")"
  fi
  cmp -s "$tmp/w$w/s.state" "$tmp/ren/s.state" && ok ||
    bad "killsave $n:write:$w: the state file is not the previous save's"
  out=$("$s42" run "$prog" --restart --state "$tmp/w$w/s.state" --dump 2>/dev/null | r2)
  [ "$out" = "end $want" ] && ok || bad "killsave $n:write:$w: restart gave '$out', want 'end $want'"
  ls "$tmp"/w$w/s.state.tmp* >/dev/null 2>&1 && bad "killsave $n:write:$w: the restart's saves left $(ls "$tmp/w$w")" || ok
done
ks "$tmp/first" "1:write:2"                  # inside the first save: nothing to restart from
out=$("$s42" run "$prog" --restart --state "$tmp/first/s.state" --dump 2>/dev/null | r2)
[ "$KST" = 137 ] && [ ! -e "$tmp/first/s.state" ] && [ "$out" = "error E-STATE" ] && ok ||
  bad "killsave 1:write:2: status $KST, restart gave '$out', files $(ls "$tmp/first")"

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

# A dialect without a save word (the 2У22): --state keeps where a run
# stopped (Стоп, the script's end), --restart goes on from there exactly as
# the run would have gone on: the same rows, the same time.
t_case u22
u22=programs/2u22/fig1_9.u22
mkdir -p "$tmp/u22"
printf 'at N10 key STOP\n' > "$tmp/u22/stop.op"
"$s42" run "$u22" --trace=json > "$tmp/u22/whole" 2>/dev/null
"$s42" run "$u22" --operator "$tmp/u22/stop.op" --state "$tmp/u22/u.state" --trace=json > "$tmp/u22/first" 2>"$tmp/u22/err"; st1=$?
[ "$st1" = 3 ] && grep -q "where the run stopped is saved in $tmp/u22/u.state" "$tmp/u22/err" && ok ||
  bad "the stop at N10: status $st1, $(tail -n 2 "$tmp/u22/err")"
"$s42" run "$u22" --restart --state "$tmp/u22/u.state" --trace=json --dump > "$tmp/u22/rest" 2>/dev/null; st2=$?
# the rows from N10 on, without their seq: those of the whole run
strip() { sed 's/^{"seq":[0-9]*,//' "$1"; }
strip "$tmp/u22/whole" | sed -n '/"n":10,/,$p' > "$tmp/u22/want"
grep '^{"seq"' "$tmp/u22/rest" | sed 's/^{"seq":[0-9]*,//' > "$tmp/u22/got"
[ "$st2" = 0 ] && [ -s "$tmp/u22/want" ] && cmp -s "$tmp/u22/want" "$tmp/u22/got" && ok ||
  bad "the restart at N10 (status $st2) differs from the whole run: $(diff "$tmp/u22/want" "$tmp/u22/got" | head -n 4)"
tail -n 1 "$tmp/u22/rest" | grep -q '"status":"end","error":null,"blocks":19,' && ok ||
  bad "the restart's dump: $(tail -n 1 "$tmp/u22/rest" | head -c 200)"
# another program text, a damaged file: refused, status 1
cp "$u22" "$tmp/u22/other.u22"
sed -i 's/^N19 M02/N19 M05 M02/' "$tmp/u22/other.u22"
"$s42" run "$tmp/u22/other.u22" --restart --state "$tmp/u22/u.state" > /dev/null 2>"$tmp/u22/err"; st3=$?
[ "$st3" = 1 ] && grep -q "restart refused: the program text changed" "$tmp/u22/err" && ok || bad "another text: status $st3"
printf 'x' | dd of="$tmp/u22/u.state" bs=1 seek=40 conv=notrunc 2>/dev/null
"$s42" run "$u22" --restart --state "$tmp/u22/u.state" > /dev/null 2>"$tmp/u22/err"; st4=$?
[ "$st4" = 1 ] && grep -q "is damaged (checksum)" "$tmp/u22/err" && ok || bad "a damaged state: status $st4"

t_done
