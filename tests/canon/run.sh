#!/bin/sh
# --trace=canon (contracts.md sec. 8): each case's calls on the machine,
# exactly, as LinuxCNC's canonical calls.   usage: run.sh S42
S42=${1:-./s42}
DIR=$(dirname "$0")
pass=0 fail=0
for kp in "$DIR"/*.kp; do
  want=${kp%.kp}.canon
  got=$("$S42" run "$kp" --trace=canon 2>&1)
  st=$?
  if [ $st -eq 0 ] && [ "$got" = "$(cat "$want")" ]; then
    pass=$((pass + 1))
  else
    echo "FAIL canon $(basename "$kp"): status $st"
    printf '%s\n' "$got" | diff "$want" - | sed 's/^/    /'
    fail=$((fail + 1))
  fi
done
echo "canon: $pass passed, $fail failed"
[ $fail -eq 0 ]
