#!/bin/sh
# Run every programs/2u22/NAME.u22 against NAME.expect.json through the shared
# conformance runner: each program becomes a temporary case folder
# (program.u22, expect.json, operator.txt from NAME.operator when there is
# one), and RUNPY compares s42's --trace=json --dump with it.  The expect.json
# names "dialect": "2u22", so the runner passes --dialect 2u22.
# Usage: programs/2u22/run.sh S42 RUNPY   (RUNPY: shared/conformance/run.py
# or the project's copy tests/conformance/run.py).  Exit 1 on any failure.
. "$(dirname "$0")/../../tests/lib.sh"
if [ $# -ne 2 ]; then
  echo "usage: $0 S42 RUNPY" >&2
  exit 2
fi
s42=$1
runpy=$2
case $s42 in /*) ;; *) s42=$(pwd)/$s42 ;; esac
here=$(cd "$(dirname "$0")" && pwd)
t_init programs-2u22
n=0
for prog in "$here"/*.u22; do
  name=$(basename "$prog" .u22)
  if [ ! -f "$here/$name.expect.json" ]; then
    bad "$name.u22 has no $name.expect.json"
    continue
  fi
  mkdir "$T/$name"
  cp "$prog" "$T/$name/program.u22"
  cp "$here/$name.expect.json" "$T/$name/expect.json"
  [ -f "$here/$name.operator" ] && cp "$here/$name.operator" "$T/$name/operator.txt"
  n=$((n + 1))
done
[ "$n" -gt 0 ] || bad "no programs found in $here"
# the runner prints "ok NAME" / "FAIL NAME: ..." per program and exits 1 on a failure
if python3 "$runpy" --s42 "$s42" "$T" >"$T/out" 2>&1; then ok; else bad "the conformance runner reported failures"; fi
sed 's/^/  /' "$T/out"
t_done
