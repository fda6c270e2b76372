#!/bin/sh
# Kill `s42 run` with SIGKILL at many points of a long cycle with M15 and
# restart it: every restart must either continue from a consistent state
# (and end with the right sum) or refuse cleanly with E-STATE -- never use a
# half-written state.  Then damage the state file in several ways and check
# that the restart is refused.
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
  ls "$tmp"/*.tmp* >/dev/null 2>&1 && rm -f "$tmp"/*.tmp*   # a killed write leaves only its temporary file
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

echo "restart: $pass passed, $fail failed"
[ "$fail" = 0 ]
