#!/bin/sh
# --realtime paces a run at machine speed: a program of 0.5 simulated
# seconds must not end sooner than that (a lower bound only: a loaded
# machine may take longer), while a run without it takes no such time.
s42=$1
prog=$(mktemp)
trap 'rm -f "$prog"' EXIT
printf '№1 G04 X+2 ^\n№2 G01 X+600 F120 ^\n№3 M02 ^\n' > "$prog"   # 0.2 s + 0.3 s
ms() { date +%s%3N; }
a=$(ms); "$s42" run "$prog" --realtime >/dev/null || { echo "realtime: 0 passed, 1 failed"; exit 1; }; b=$(ms)
took=$((b - a))
if [ "$took" -ge 480 ]; then
  echo "realtime: 0.5 s simulated took ${took} ms"
  echo "realtime: 1 passed, 0 failed"
else
  echo "FAIL realtime: 0.5 s simulated took only ${took} ms"
  echo "realtime: 0 passed, 1 failed"
  exit 1
fi
