#!/bin/sh
# Run every programs/NAME.kp against NAME.expect.json with the conformance
# runner: each program becomes a temporary case folder (program.kp,
# operator.txt, tool.txt, expect.json), then shared/conformance/run.py compares.
# Usage: programs/run_expect.sh [S42] [RUN_PY]   (from the repository root)
set -e
here=$(cd "$(dirname "$0")" && pwd)
s42=${1:-"$here/../s42"}
runpy=${2:-"$here/../../shared/conformance/run.py"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for kp in "$here"/*.kp; do
  name=$(basename "$kp" .kp)
  [ -f "$here/$name.expect.json" ] || continue
  mkdir "$tmp/$name"
  cp "$kp" "$tmp/$name/program.kp"
  cp "$here/$name.expect.json" "$tmp/$name/expect.json"
  [ -f "$here/$name.operator" ] && cp "$here/$name.operator" "$tmp/$name/operator.txt"
  [ -f "$here/$name.tool" ] && cp "$here/$name.tool" "$tmp/$name/tool.txt"
done
python3 "$runpy" --s42 "$s42" "$tmp"
