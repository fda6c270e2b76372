#!/bin/sh
# The five-minute tutorial of README.md, every step as the README gives it
# (make, check, run, plot, the terminal in tmux, the restart), on a copy of
# the repository; and the man page rendered without a warning.
#   sh tests/tutorial/run.sh
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
exec python3 "$HERE/tutorial.py" "$ROOT"
