#!/bin/sh
# The training run of the front end's profile feedback (Makefile, PGO=1).
#
# An instrumented s42 (built into BUILD/pgo/gen with -fprofile-generate)
# compiles every program of the repository: the bundled programs, the
# error programs, the guide's examples and the tests' programs.  Left out:
# the benchmarks' programs (bench/), so that `make bench` measures a build
# that never saw its input, and the fuzz corpus, 7.5 MB of mostly broken
# text that would make the error paths look like the common ones.
# The counts of the front end's files (PGO_SRCS) are then copied to
# BUILD/pgo/use, and the stamp touched, only when they changed: the
# training is deterministic, so an edit elsewhere retrains but recompiles
# nothing of the front end.
#
# Usage: scripts/pgo-train.sh S42 COUNTS USE PLUGINS SRC...
#   S42      the instrumented binary
#   COUNTS   where it writes its .gcda files (its -fprofile-generate=DIR)
#   USE      where the optimized build reads them (-fprofile-use=DIR)
#   PLUGINS  the plugins to load (the build's plugins folder)
#   SRC...   the front end's sources, whose counts are kept
set -e
s42=$1 counts=$2 use=$3 plugins=$4
shift 4
rm -rf "$counts"
mkdir -p "$counts" "$use"

# (from the repository's root; status 0 or 1: many of these programs have
# errors on purpose; anything else is a crash of the instrumented build)
files=$(find programs docs tests -type f -name '*.kp' | sort)
st=0
"$s42" check --plugins "$plugins" $files >/dev/null 2>&1 || st=$?
if [ "$st" -gt 1 ]; then
  echo "pgo-train: the instrumented s42 check ended with status $st" >&2
  exit 1
fi

changed=
for src in "$@"; do
  # GCC names a unit's counts after its object, relative to the build
  # (-fprofile-prefix-path): src/core/x.c -> src#core#x.gcda
  name=$(echo "${src%.c}" | tr / '#').gcda
  if [ ! -f "$counts/$name" ]; then
    echo "pgo-train: the training wrote no counts for $src ($counts/$name)" >&2
    exit 1
  fi
  if ! cmp -s "$counts/$name" "$use/$name"; then
    cp "$counts/$name" "$use/$name"
    changed=1
  fi
done
if [ -n "$changed" ] || [ ! -f "$use/stamp" ]; then
  touch "$use/stamp"
  echo "pgo-train: new counts for the front end's $# files in $use"
fi
