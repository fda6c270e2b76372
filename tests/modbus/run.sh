#!/bin/sh
# The Modbus server (contracts.md sec. 6): a libmodbus client runs a program
# through Modbus alone, malformed frames while another client measures its
# round trips (raw.py), the server under load (robust.py), and mbpoll, a
# client no one here wrote, drives bundled programs from Пуск to M2.  Every
# wait has a time limit.
#   run.sh S42 CLIENT
s42=$1
client=$2
py=${PYTHON:-python3}
dir=$(dirname "$0")
. "$dir/../lib.sh"
t_init modbus
tmp=$T
SPID=
t_atexit '[ -n "$SPID" ] && kill -KILL "$SPID" 2>/dev/null'
fail() { bad "$*"; }

# start ARGS...: s42 run ARGS --modbus on a free port; sets PORT and SPID.
start() {
  tries=0
  while [ $tries -lt 20 ]; do
    PORT=$(t_port)
    rm -f "$tmp/err"
    "$s42" run "$@" --modbus "127.0.0.1:$PORT" >"$tmp/out" 2>"$tmp/err" &
    SPID=$!
    i=0
    while [ $i -lt 100 ]; do
      grep -q "Modbus TCP on 127.0.0.1:$PORT" "$tmp/err" 2>/dev/null && return 0
      kill -0 "$SPID" 2>/dev/null || break
      sleep 0.05
      i=$((i + 1))
    done
    kill -KILL "$SPID" 2>/dev/null
    wait "$SPID"
    st=$?
    SPID=
    if [ $st -eq 4 ] && grep -q "in use" "$tmp/err"; then tries=$((tries + 1)); continue; fi
    fail "the server did not start (status $st): $(cat "$tmp/err")"
    return 1
  done
  fail "no free port in 20 tries"
  return 1
}

# stop: SIGTERM, then the exit status in STATUS (SIGKILL after 5 s).
stop() {
  t_stop "$SPID" 5
  STATUS=$T_STATUS
  SPID=
}

# mbp ARGS...: mbpoll once against the server, 0-based addresses.
mbp() { timeout 10 mbpoll -m tcp -p "$PORT" -0 -1 -o 2 "$@" 2>&1; }
# value REF ARGS...: the value mbpoll reads at REF
value() { ref=$1; shift; mbp -r "$ref" "$@" 127.0.0.1 | sed -n "s/^\[$ref\]:[[:space:]]*//p"; }
# wait_state N: poll input register 2 with mbpoll until it is N (10 s)
state_is() { [ "$(value 2 -t 3)" = "$1" ]; }
wait_state() { t_wait 10 state_is "$1"; }

# 1. the libmodbus client: loop.kp through Modbus alone (paced, to see it run)
if start "$dir/loop.kp" --realtime; then
  if timeout 60 "$client" "$PORT" >"$tmp/client"; then ok; else fail "the libmodbus client test"; fi
  cat "$tmp/client"
  stop
  [ "$STATUS" = 0 ] && ok || fail "SIGTERM after M2: status $STATUS, expected 0"
fi

# 2. malformed frames while another client measures its round trips
if start "$dir/loop.kp" --realtime; then
  if timeout 90 "$py" "$dir/raw.py" "$PORT"; then ok; else fail "the malformed-frame test"; fi
  kill -0 "$SPID" 2>/dev/null && ok || fail "the server died under malformed frames"
  stop
  [ "$STATUS" = 3 ] && ok || fail "SIGTERM before Пуск: status $STATUS, expected 3"
fi

# 3. robustness (tests/modbus/robust.py): pipelined requests, full slots,
# active clients never closed for a newcomer (issue 30), the per-address
# cap, idle connections, read-only and allow-listed servers, a machine whose
# stdout nobody reads, a tooth search that computes for seconds
rb() { timeout 120 "$py" "$dir/robust.py" "$@"; }
if start "$dir/loop.kp"; then
  rb pipeline "$PORT" && ok || fail "pipelined requests"
  stop
fi
if start "$dir/loop.kp"; then
  rb slots "$PORT" 8 && ok || fail "8 slots full"
  stop
fi
if start "$dir/loop.kp" --modbus-max-clients 3; then
  rb slots "$PORT" 3 && ok || fail "--modbus-max-clients 3"
  stop
fi
if start "$dir/loop.kp"; then
  rb busy "$PORT" && ok || fail "seven busy clients and a loop of newcomers: the panel polling every 100 ms lost polls"
  stop
fi
if start "$dir/loop.kp" --modbus-max-clients 3; then
  rb full "$PORT" 3 && ok || fail "every slot active: a newcomer was not refused, or closed an active client"
  stop
fi
if start "$dir/loop.kp" --modbus-max-clients 3 --modbus-read-only --modbus-allow 127.0.0.0/8; then
  rb full "$PORT" 3 && ok || fail "every slot active, --modbus-read-only and --modbus-allow: not the same"
  stop
fi
for n in 8 2; do
  if start "$dir/loop.kp" --modbus-max-clients $n; then
    rb perhost "$PORT" $n && ok || fail "--modbus-max-clients $n: one address took more than $((n - 1))"
    stop
  fi
done
if start "$dir/loop.kp" --modbus-idle 0.6; then
  rb idle "$PORT" 0.6 && ok || fail "--modbus-idle 0.6"
  stop
fi
if start "$dir/loop.kp" --modbus-read-only; then
  rb readonly "$PORT" && ok || fail "--modbus-read-only"
  stop
fi
if start "$dir/loop.kp" --modbus-allow 10.1.0.0/16,::2; then
  rb refused "$PORT" && ok || fail "--modbus-allow without loopback"
  stop
fi
if start "$dir/loop.kp" --modbus-allow 192.168.0.0/16,127.0.0.0/8; then
  rb probe "$PORT" 0.3 >/dev/null && ok || fail "--modbus-allow 127.0.0.0/8 refused loopback"
  grep -q "warning" "$tmp/err" && fail "a warning on a loopback address: $(cat "$tmp/err")" || ok
  stop
fi
for bad in "--modbus-idle 1" "--modbus --modbus-max-clients 0" "--modbus --modbus-max-clients 257" \
           "--modbus --modbus-idle -1" "--modbus --modbus-idle x" "--modbus-read-only" \
           "--modbus --modbus-allow 300.1.1.1" "--modbus --modbus-allow 10.0.0.0/33" "--modbus --modbus-allow 10.0.0.1,"; do
  # shellcheck disable=SC2086
  timeout 10 "$s42" run "$dir/loop.kp" $bad 2>"$tmp/e" </dev/null; st=$?
  [ $st = 2 ] && [ -s "$tmp/e" ] && ok || fail "$bad: status $st, expected 2: $(cat "$tmp/e")"
done
# a server on every interface without an allow list says so (read-only, briefly)
P2=$(t_port)
timeout 1 "$s42" run "$dir/loop.kp" --modbus "0.0.0.0:$P2" --modbus-read-only 2>"$tmp/e"
grep -q "warning: Modbus on 0.0.0.0:$P2: not a loopback address" "$tmp/e" || grep -q "in use" "$tmp/e" && ok ||
  fail "no warning on 0.0.0.0 without --modbus-allow: $(cat "$tmp/e")"
rb stall "$s42" "$dir/loop.kp" && ok || fail "a trace into a pipe nobody reads stalled the server"
# the biggest image, blurred 8 px (the blur's cost grows with it): each of
# the two sections computes for over a second, not 0.4 s that a fast machine
# made shorter than the 0.5 s the tests need to measure round trips in
sed -e 's/^image .*/image    = 4096/' -e 's/^blur .*/blur     = 8/' programs/endmill_search.tool >"$tmp/big.tool"
grep -q '^blur     = 8$' "$tmp/big.tool" && ok || fail "the big tool has no blur of 8 px"
rb search "$s42" programs/endmill_search.kp --tool "$tmp/big.tool" --operator programs/endmill_search.operator \
  --state "$tmp/es.state" && ok || fail "a long tooth search stalled the server"

# 4. bad addresses and a port in use
"$s42" run "$dir/loop.kp" --modbus 127.0.0.1:99999 2>"$tmp/e"; st=$?
[ $st = 2 ] && ok || fail "--modbus 127.0.0.1:99999: status $st, expected 2"
"$s42" run "$dir/loop.kp" --modbus=no.such.host.invalid:1502 2>"$tmp/e"; st=$?
[ $st = 2 ] && ok || fail "--modbus=no.such.host.invalid:1502: status $st, expected 2"
if start "$dir/loop.kp"; then
  timeout 10 "$s42" run "$dir/loop.kp" --modbus "127.0.0.1:$PORT" 2>"$tmp/e"; st=$?
  [ $st = 4 ] && grep -q "in use" "$tmp/e" && ok || fail "a port in use: status $st, expected 4: $(cat "$tmp/e")"
  stop
fi

# 5. mbpoll
if ! command -v mbpoll >/dev/null 2>&1; then
  echo "modbus: mbpoll is not installed (Debian package mbpoll): its tests were skipped"
else
  # parameters and a torn write
  if start "$dir/loop.kp"; then
    [ "$(value 0 -t 3:hex)" = 0x0100 ] && ok || fail "mbpoll: map version"
    mbp -B -t 4:float -r 602 127.0.0.1 4.5 >/dev/null && ok || fail "mbpoll: write R1 as float32"
    [ "$(value 602 -B -t 3:float)" = 4.5 ] && ok || fail "mbpoll: R1 reads $(value 602 -B -t 3:float)"
    [ "$(value 104 -t 3:hex)" = 0x4012 ] && ok || fail "mbpoll: R1 as float64 does not begin 0x4012"
    out=$(mbp -B -t 4:float -r 101 127.0.0.1 1.0) && fail "mbpoll: a torn write (float32 into a float64) was taken"
    echo "$out" | grep -q "Illegal data address" && ok || fail "mbpoll: torn write: $out"
    out=$(mbp -B -t 4:int -r 100 127.0.0.1 7) && fail "mbpoll: half a float64 was taken"
    echo "$out" | grep -q "Illegal data address" && ok || fail "mbpoll: half a float64: $out"
    stop
  fi
  # the override within a block's motion (holding register 0), 0 % holds it,
  # reset keeps it; the snapshot counter beats with no request; single
  # block (coil 5) and the breakpoint (holding register 2)
  printf '%s\n' '; a 60 s stroke at F60, then short blocks' '№1 G01 X+60000 F60 ^' '№2 G01 X-1000 F600 ^' \
    '№3 G01 X-1000 ^' '№4 G01 X-1000 ^' '№5 M02 ^' >"$tmp/long.kp"
  feed() { mbp -B -t 3:int -r 18 127.0.0.1 | sed -n 's/^\[18\]:[[:space:]]*//p'; }
  xpos() { mbp -B -t 3:int -r 10 127.0.0.1 | sed -n 's/^\[10\]:[[:space:]]*//p'; }
  feed_is() { [ "$(feed)" = "$1" ]; }
  moved_past() { [ "$(feed)" = 60000 ] && [ "$(xpos)" -gt "$1" ]; }   # at 100 %, X beyond $1
  waits_at() { [ "$(value 2 -t 3)" = 3 ] && [ "$(value 3 -t 3)" = "$1" ]; }   # run state 3 at block $1
  if start "$tmp/long.kp" --realtime; then
    c1=$(value 1 -t 3); sleep 1.1; c2=$(value 1 -t 3)
    [ -n "$c1" ] && [ $((c2 - c1)) -ge 4 ] && ok || fail "mbpoll: the snapshot counter went $c1 -> $c2 in 1.1 s idle"
    [ "$(value 5 -t 3)" = 100 ] && ok || fail "mbpoll: override in effect $(value 5 -t 3) while idle, expected 100"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    wait_state 1 && ok || fail "mbpoll override: no run after Пуск"
    [ "$(feed)" = 60000 ] && ok || fail "mbpoll override: feed $(feed), expected 60000 (0.001 mm/min)"
    mbp -t 4 -r 0 127.0.0.1 150 >/dev/null
    t_wait 1 feed_is 90000 && ok || fail "mbpoll override: feed $(feed) after 150 % within N1, expected 90000"
    [ "$(value 3 -t 3)" = 1 ] && ok || fail "mbpoll override: block $(value 3 -t 3), expected still N1"
    mbp -t 4 -r 0 127.0.0.1 0 >/dev/null
    wait_state 2 && ok || fail "mbpoll override: 0 % within a move: run state $(value 2 -t 3), expected 2"
    [ "$(feed)" = 0 ] && ok || fail "mbpoll override: feed $(feed) at 0 %, expected 0"
    x1=$(xpos); sleep 0.4; x2=$(xpos)
    [ -n "$x1" ] && [ "$x1" = "$x2" ] && ok || fail "mbpoll override: X moved at 0 % ($x1, $x2)"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null     # Пуск does not move it at 0 %
    sleep 0.3
    [ "$(xpos)" = "$x2" ] && ok || fail "mbpoll override: Пуск moved X at 0 %"
    mbp -t 4 -r 0 127.0.0.1 100 >/dev/null
    wait_state 1 && ok || fail "mbpoll override: 100 % again: run state $(value 2 -t 3)"
    t_wait 2 moved_past "$x2" && ok || fail "mbpoll override: 100 %: feed $(feed), X $(xpos)"
    mbp -t 4 -r 0 127.0.0.1 40 >/dev/null
    mbp -t 0 -r 4 127.0.0.1 1 >/dev/null     # reset: the switch keeps its position
    wait_state 0 && ok || fail "mbpoll: no idle after reset"
    [ "$(value 5 -t 3)" = 40 ] && [ "$(value 0 -t 4)" = 40 ] && ok ||
      fail "mbpoll: override after reset: in effect $(value 5 -t 3), register $(value 0 -t 4), expected 40"
    stop
  fi
  if start "$tmp/long.kp"; then
    mbp -t 0 -r 5 127.0.0.1 1 >/dev/null     # single block on
    [ "$(value 5 -t 0)" = 1 ] && ok || fail "mbpoll: coil 5 reads $(value 5 -t 0) after single block on"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    wait_state 3 && [ "$(value 3 -t 3)" = 2 ] && ok || fail "mbpoll single: N2 does not wait (block $(value 3 -t 3))"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    t_wait 10 waits_at 3 && ok || fail "mbpoll single: N3 does not wait (block $(value 3 -t 3))"
    mbp -t 0 -r 5 127.0.0.1 0 >/dev/null     # automatic, a breakpoint at N5
    mbp -t 4 -r 2 127.0.0.1 5 >/dev/null
    [ "$(value 2 -t 4)" = 5 ] && ok || fail "mbpoll: holding register 2 reads $(value 2 -t 4), expected 5"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    t_wait 10 waits_at 5 && ok || fail "mbpoll break: N5 does not wait (block $(value 3 -t 3))"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    wait_state 5 && ok || fail "mbpoll break: no M2 after Пуск at N5"
    stop
  fi
  # programs from programs/ from start to M2, driven only by mbpoll commands
  for prog in drill_point tap_chamfer; do
    start "programs/$prog.kp" --dump || continue
    [ "$(value 2 -t 3)" = 0 ] && ok || fail "mbpoll $prog: not idle before Пуск"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null || fail "mbpoll $prog: Пуск"
    if [ $prog = tap_chamfer ]; then   # a G20 stop: Пуск again
      wait_state 3 && ok || fail "mbpoll $prog: no G20 wait"
      [ "$(value 3 -t 3)" = 3 ] && ok || fail "mbpoll $prog: the wait is not at N3"
      mbp -t 0 -r 0 127.0.0.1 1 >/dev/null || fail "mbpoll $prog: second Пуск"
    fi
    wait_state 5 && ok || fail "mbpoll $prog: never reached M2 (state $(value 2 -t 3))"
    pos=$(mbp -B -t 3:int -r 10 -c 4 127.0.0.1 | sed -n 's/^\[1[0-6]\]:[[:space:]]*//p' | tr '\n' ' ')
    stop
    [ "$STATUS" = 0 ] && ok || fail "mbpoll $prog: status $STATUS after M2, expected 0"
    want=$("$py" -c "import json,sys; p=json.load(open(sys.argv[1]))['pos']; print(p['x'],p['y'],p['z'],p['a'],'')" "$tmp/out" 2>/dev/null)
    [ -n "$want" ] && [ "$pos" = "$want" ] && ok || fail "mbpoll $prog: positions '$pos', the dump says '$want'"
  done
  # a program with plugins (helix, oscillation): Пуск after M2 runs it again
  if start programs/helical_flute.kp; then
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    wait_state 5 && ok || fail "mbpoll helical_flute: first cycle never reached M2 (state $(value 2 -t 3))"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    sleep 0.5
    wait_state 5 && [ "$(value 4 -t 3)" = 0 ] && ok ||
      fail "mbpoll helical_flute: the second cycle: state $(value 2 -t 3), error $(value 4 -t 3)"
    stop
  fi

  # the 2У22 lathe on the same server (contracts.md sec. 6, its map): R0-R9
  # and none beyond (02), Пуск, X (a diameter) and Z in µm at 10..13 as its
  # dump has them, a written R1 that the program uses (N5 X+R1)
  printf '%s\n' '%' 'N1 T1 G01 G90 G94 G97 S500 M03 M39 M08' 'N2 F300 X4000 Z0' 'N3 G20 F100 Z-3000' \
    'N4 F1000 X+R1' 'N5 M02' >"$tmp/lathe.u22"
  if start "$tmp/lathe.u22" --dump; then
    [ "$(value 2 -t 3)" = 0 ] && ok || fail "mbpoll 2У22: not idle before Пуск"
    mbp -B -t 4:float -r 602 127.0.0.1 5000 >/dev/null && ok || fail "mbpoll 2У22: write R1 as float32"
    [ "$(value 602 -B -t 3:float)" = 5000 ] && ok || fail "mbpoll 2У22: R1 reads $(value 602 -B -t 3:float)"
    out=$(mbp -B -t 4:float -r 620 127.0.0.1 1) && fail "mbpoll 2У22: R10 was written: the lathe has R0-R9"
    echo "$out" | grep -q "Illegal data address" && ok || fail "mbpoll 2У22: R10 write: $out"
    out=$(mbp -B -t 3:float -r 620 127.0.0.1) && fail "mbpoll 2У22: R10 was read"
    echo "$out" | grep -q "Illegal data address" && ok || fail "mbpoll 2У22: R10 read: $out"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null || fail "mbpoll 2У22: Пуск"
    wait_state 5 && ok || fail "mbpoll 2У22: never reached M02 (state $(value 2 -t 3))"
    pos=$(mbp -B -t 3:int -r 10 -c 2 127.0.0.1 | sed -n 's/^\[1[02]\]:[[:space:]]*//p' | tr '\n' ' ')
    stop
    [ "$STATUS" = 0 ] && ok || fail "mbpoll 2У22: status $STATUS after M02, expected 0"
    want=$("$py" -c "import json,sys; p=json.load(open(sys.argv[1]))['pos']; print(round(p['x']*1000),round(p['z']*1000),'')" "$tmp/out" 2>/dev/null)
    [ "$pos" = "50000 -30000 " ] && [ "$pos" = "$want" ] && ok ||
      fail "mbpoll 2У22: positions '$pos', the dump says '$want', expected '50000 -30000 '"
  fi
  # F% (holding register 0) under --realtime: kept but not acting under G23
  # (N2), acting under G20 (N3) and within its move, re-timing the rest
  # from where Z is (the speed: Z against the simulated time, one read);
  # 0 % holds it; the spindle and coolant at discrete inputs 5 and 6
  zt() { mbp -B -t 3:int -r 12 -c 5 127.0.0.1 | sed -n -e 's/^\[12\]:[[:space:]]*//p' -e 's/^\[20\]:[[:space:]]*//p' | tr '\n' ' '; }
  # speed_is LO HI: Z's speed over 0.4 s, µm per simulated ms, within LO..HI
  speed_is() {
    set -- "$1" "$2" $(zt)
    sleep 0.4
    set -- "$@" $(zt)
    [ $# = 6 ] && [ "$6" -gt "$4" ] && "$py" -c "import sys; lo,hi,z1,t1,z2,t2=map(float,sys.argv[1:]); v=(z1-z2)/(t2-t1); sys.exit(0 if lo<=v<=hi else 1)" "$@"
  }
  runs_at() { [ "$(value 2 -t 3)" = 1 ] && [ "$(value 3 -t 3)" = "$1" ]; }
  if start "$tmp/lathe.u22" --realtime; then
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    t_wait 10 runs_at 2 && ok || fail "mbpoll 2У22 override: N2 does not run (block $(value 3 -t 3))"
    [ "$(value 5 -t 1)" = 1 ] && [ "$(value 6 -t 1)" = 1 ] && [ "$(value 7 -t 1)" = 1 ] && ok ||
      fail "mbpoll 2У22: discrete inputs 5-7 (spindle, coolant, X moving) read $(value 5 -t 1 -c 3)"
    mbp -t 4 -r 0 127.0.0.1 50 >/dev/null && ok || fail "mbpoll 2У22: override 50 under G23 refused"
    [ "$(value 0 -t 4)" = 50 ] && [ "$(value 5 -t 3)" = 100 ] && [ "$(feed)" = 300000 ] && ok ||
      fail "mbpoll 2У22 G23: register $(value 0 -t 4), in effect $(value 5 -t 3), feed $(feed): expected 50, 100, 300000"
    t_wait 10 runs_at 3 && ok || fail "mbpoll 2У22 override: N3 does not run (block $(value 3 -t 3))"
    [ "$(value 10 -B -t 3:int)" = 40000 ] && [ "$(value 8 -t 1)" = 1 ] && ok ||
      fail "mbpoll 2У22: X $(value 10 -B -t 3:int) (expected 40000), Z moving $(value 8 -t 1)"
    [ "$(value 5 -t 3)" = 50 ] && [ "$(feed)" = 50000 ] && ok ||
      fail "mbpoll 2У22 G20: in effect $(value 5 -t 3), feed $(feed): expected 50, 50000"
    speed_is 0.75 0.92 && ok || fail "mbpoll 2У22: Z does not go at 50 mm/min at 50 % ($(zt))"
    mbp -t 4 -r 0 127.0.0.1 100 >/dev/null
    t_wait 1 feed_is 100000 && ok || fail "mbpoll 2У22: feed $(feed) after 100 % within N3, expected 100000"
    [ "$(value 3 -t 3)" = 3 ] && [ "$(value 5 -t 3)" = 100 ] && ok || fail "mbpoll 2У22: not N3 at 100 %"
    speed_is 1.55 1.8 && ok || fail "mbpoll 2У22: Z does not go at 100 mm/min at 100 % ($(zt))"
    mbp -t 4 -r 0 127.0.0.1 0 >/dev/null
    wait_state 2 && [ "$(feed)" = 0 ] && ok || fail "mbpoll 2У22: 0 %: run state $(value 2 -t 3), feed $(feed)"
    z1=$(zt); sleep 0.4; z2=$(zt)
    [ -n "$z1" ] && [ "$z1" = "$z2" ] && ok || fail "mbpoll 2У22: Z moved at 0 % ($z1, $z2)"
    mbp -t 4 -r 0 127.0.0.1 150 >/dev/null
    wait_state 1 && t_wait 1 feed_is 150000 && ok || fail "mbpoll 2У22: 150 %: state $(value 2 -t 3), feed $(feed)"
    speed_is 2.3 2.7 && ok || fail "mbpoll 2У22: Z does not go on at 150 mm/min from where it stood ($z2; $(zt))"
    stop
    [ "$STATUS" = 3 ] && ok || fail "mbpoll 2У22: SIGTERM within N3: status $STATUS, expected 3"
  fi
fi

# 6. s42 tui --modbus in tmux: a client's keys are the panel's keys, the map
# shows what the terminal shows
if ! t_have mbpoll || ! t_have tmux; then
  echo "modbus: mbpoll or tmux is not installed: the terminal's Modbus tests were skipped"
else
  . "$dir/../tmux.sh"                         # the terminal tests' driver
  tm_init "$tmp"
  screen_has() { tm_wait mb -J "$1" 5; }      # screen_has TEXT: within 5 s, the rows joined
  PORT=$(t_port)
  tm_run mb 120 40 . -e LANG=C.UTF-8 "$s42" tui programs/drill_point.kp --modbus "127.0.0.1:$PORT"
  if screen_has "Modbus TCP on 127.0.0.1:$PORT"; then
    ok
    [ "$(value 2 -t 3)" = 0 ] && ok || fail "tui: not idle before Пуск"
    [ "$(value 5 -t 3)" = 100 ] && ok || fail "tui: override in effect $(value 5 -t 3) while idle, expected 100"
    mbp -t 0 -r 5 127.0.0.1 1 >/dev/null
    screen_has "single block (П)" && ok || fail "tui: coil 5 did not set single block"
    [ "$(value 5 -t 0)" = 1 ] && ok || fail "tui: coil 5 reads $(value 5 -t 0)"
    mbp -t 0 -r 5 127.0.0.1 0 >/dev/null
    screen_has "automatic (АВТ)" && ok || fail "tui: coil 5 = 0 did not set automatic"
    mbp -t 4 -r 2 127.0.0.1 7 >/dev/null
    screen_has "breakpoint at N7" && ok || fail "tui: holding register 2 did not set the breakpoint"
    mbp -t 4 -r 2 127.0.0.1 0 >/dev/null
    screen_has "no breakpoint" && ok || fail "tui: holding register 2 = 0 did not clear the breakpoint"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    screen_has "Пуск: the cycle starts" && ok || fail "tui: a client's Пуск did not start the cycle"
    wait_state 1 && ok || fail "tui: run state not 1 after Пуск"
    [ "$(value 3 -t 3)" -ge 40 ] 2>/dev/null && ok || fail "tui: block number $(value 3 -t 3) while in sub 40"
    mbp -t 0 -r 1 127.0.0.1 1 >/dev/null
    screen_has "feed hold" && ok || fail "tui: a client's Стоп was not a feed hold"
    wait_state 2 && ok || fail "tui: run state not 2 (stopped) after Стоп"
    mbp -t 4 -r 0 127.0.0.1 50 >/dev/null
    screen_has "feed override 50 %" && ok || fail "tui: the override write did not reach the panel"
    [ "$(value 0 -t 4)" = 50 ] && ok || fail "tui: holding register 0 reads $(value 0 -t 4), expected 50"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    screen_has "the motion goes on" && ok || fail "tui: Пуск after Стоп did not resume"
    mbp -t 0 -r 4 127.0.0.1 1 >/dev/null
    screen_has "reset: the machine is idle" && ok || fail "tui: reset"
    wait_state 0 && ok || fail "tui: run state not 0 after reset"
    mbp -t 0 -r 0 127.0.0.1 1 >/dev/null
    wait_state 1 && ok || fail "tui: Пуск after reset"
    tm_keys mb f                    # as fast as possible: to M2
    wait_state 5 && ok || fail "tui: never reached M2 (state $(value 2 -t 3))"
    tm_keys mb q
    tm_ended mb 5
    [ "$TM_STATUS" = exit=0 ] && ok || fail "tui: status '$TM_STATUS' after q"
  else
    fail "tui --modbus did not start: $(tm_pane mb | head -5)"
  fi
  # the terminal computes a long tooth search; its server still answers
  PORT=$(t_port)
  tm_run mb 120 40 . -e LANG=C.UTF-8 "$s42" tui programs/endmill_search.kp --tool "$tmp/big.tool" \
    --state "$tmp/tui.state" --modbus "127.0.0.1:$PORT"
  if screen_has "Modbus TCP on 127.0.0.1:$PORT"; then
    rb tuisearch "$PORT" && ok || fail "tui: a long tooth search stalled the server"
  else
    fail "tui --modbus with the search did not start: $(tm_pane mb | head -5)"
  fi
  tm_kill mb
  tm_end
  "$s42" tui programs/drill_point.kp --modbus 127.0.0.1:99999 </dev/null >/dev/null 2>"$tmp/e"; st=$?
  [ $st = 2 ] && grep -q 99999 "$tmp/e" && ok || fail "tui --modbus 127.0.0.1:99999: status $st, expected 2"
fi

t_done
