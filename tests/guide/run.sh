#!/bin/sh
# docs/guide.md and its examples in docs/guide/: every program block is its
# file, every example runs to M2 (or fails as documented), every console
# transcript prints what the guide shows (tests/guide/check.py).
#   sh tests/guide/run.sh ./s42
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
S42=$(cd "$(dirname "${1:-./s42}")" && pwd)/$(basename "${1:-./s42}")
# under make asan: fontconfig's lifetime cache (s42 plot) is not a leak of s42
LSAN_OPTIONS="suppressions=$ROOT/tests/plot/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export LSAN_OPTIONS
exec python3 "$HERE/check.py" "$S42" "$ROOT"
