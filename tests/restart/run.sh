#!/bin/sh
# Kill `s42 run` with SIGKILL at many points of a long cycle with M15 and
# restart it: every restart must either continue from a consistent state
# (and end with the right sum) or refuse cleanly with E-STATE -- never use a
# half-written state.  Then damage the state file in several ways and check
# that the restart is refused; a --state that is not a state is never
# replaced, a failed save is E-STATE, and a killed save's temporary file is
# removed by the next save.
#   sh tests/restart/run.sh S42
s42=$1
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

echo "restart: $pass passed, $fail failed"
[ "$fail" = 0 ]
