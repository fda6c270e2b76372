#!/bin/sh
# --realtime paces a run at machine speed: a program of 0.5 simulated
# seconds must not end sooner than that (a lower bound only: a loaded
# machine may take longer), while a run without it takes no such time.
# Ctrl-C (SIGINT) or SIGTERM stop a paced run at the next block boundary
# with the dump of that moment, status 3, and a note naming the block.
s42=$1
. "$(dirname "$0")/../lib.sh"
t_init realtime
printf '№1 G04 X+2 ^\n№2 G01 X+600 F120 ^\n№3 M02 ^\n' > "$T/p.kp"   # 0.2 s + 0.3 s
a=$(t_ms); "$s42" run "$T/p.kp" --realtime >/dev/null; st=$?; b=$(t_ms)
took=$((b - a))
if [ "$st" -ne 0 ]; then
  bad "status $st"
elif [ "$took" -ge 480 ]; then
  echo "realtime: 0.5 s simulated took ${took} ms"; ok
else
  bad "0.5 s simulated took only ${took} ms"
fi

# 100 one-second dwells: interrupted after about a second
printf '№1 R1+0 ^\n№2 G04 X+10 R1+R1+1 ^\n№3 P(R1:M:100)2 ^\n№4 M02 ^\n' > "$T/long.kp"
for sig in INT TERM; do
  "$s42" run "$T/long.kp" --realtime --dump >"$T/out" 2>"$T/err" &
  pid=$!
  sleep 1.3
  kill -s $sig $pid
  wait $pid
  st=$?
  if [ "$st" -eq 3 ] && grep -q '"status":"stopped"' "$T/out" &&
     grep -Eq 'long\.kp:[0-9]+:1: note: N[23]: stopped by (Ctrl-C \(SIGINT\)|SIGTERM) before this block' "$T/err" &&
     python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if 1 <= d["r"][1] < 100 else 1)' "$T/out"; then
    ok
  else
    bad "SIG$sig: status $st, $(cat "$T/err") $(head -c 200 "$T/out")"
  fi
done
t_done
