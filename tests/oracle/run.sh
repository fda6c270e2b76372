#!/bin/sh
# The LinuxCNC oracle for the 2У22: each tests/oracle/NAME.ngc is a hand
# translation of programs/2u22/NAME.u22 (README.md here says how); rs274 -g
# runs it live, s42 runs the 2У22 program with --trace=canon (and
# --operator programs/2u22/NAME.operator when there is one), both outputs go
# through the same filter, and the two must be equal line for line.
# Usage: tests/oracle/run.sh S42   (from anywhere)
# NAME.rs274 beside each twin is what rs274 printed when the twin was written;
# the test does not read it (it is there to read, and to see rs274 changes).
. "$(dirname "$0")/../lib.sh"
if [ $# -ne 1 ]; then
  echo "usage: $0 S42" >&2
  exit 2
fi
if ! t_have rs274; then
  if [ -n "${S42_REQUIRE_ORACLE:-}" ]; then
    echo "oracle: FAIL: rs274 is not installed and S42_REQUIRE_ORACLE is set (sh scripts/deps.sh --oracle)"
    exit 1
  fi
  echo "oracle: skipped: rs274 not installed (Debian linuxcnc-uspace; sh scripts/deps.sh --oracle)"
  exit 0
fi
s42=$1
here=$(cd "$(dirname "$0")" && pwd)
progs=$here/../../programs/2u22

# canon_filter < RAW > FILTERED
#  1. strip rs274's line number and "N..... " prefix (s42 prints neither);
#  2. rs274's prologue: everything up to and including the comment that the
#     twin's first line (G21 G18 G7 G90 G94) ends with, "Lathe diameter mode
#     changed to diameter", is LinuxCNC's start-up and the mode line, not the
#     program (its SET_FEED_MODE(0, 0) / SET_FEED_RATE(0.0000) is the power-on
#     G94 the 2У22 has too, D-7); s42's output has no such comment, so nothing
#     of it is dropped;
#  3. keep only the machine calls: STRAIGHT_FEED STRAIGHT_TRAVERSE ARC_FEED
#     DWELL SET_FEED_RATE SET_FEED_MODE SET_SPINDLE_SPEED START_SPINDLE_*
#     STOP_SPINDLE_TURNING START_SPEED_FEED_SYNC STOP_SPEED_FEED_SYNCH FLOOD_*
#     MIST_* PROGRAM_END (not SELECT_TOOL: see README.md);
#  4. the tail after the last motion (STRAIGHT_*, ARC_FEED, DWELL): drop its
#     SET_FEED_MODE / SET_FEED_RATE (LinuxCNC's M2 resets G94 and F = 0; no
#     motion follows, and the 2У22's M02 stops only the spindle and the
#     coolant, D-30), then compare the rest as a set (sorted, duplicates dropped): whether a
#     spindle already stopped by M05 is stopped again by M02, and in which
#     order M02's stops print, is not part of either language.
canon_filter() {
  awk '
    { sub(/^ *[0-9]+ N\.\.\.\.\. /, "") }
    /^COMMENT\("interpreter: Lathe diameter mode changed to diameter"\)$/ { n = 0; next }
    /^(STRAIGHT_FEED|STRAIGHT_TRAVERSE|ARC_FEED|DWELL|SET_FEED_RATE|SET_FEED_MODE|SET_SPINDLE_SPEED|START_SPINDLE_|STOP_SPINDLE_TURNING|START_SPEED_FEED_SYNC|STOP_SPEED_FEED_SYNCH|FLOOD_|MIST_|PROGRAM_END)/ {
      line[++n] = $0
      if ($0 ~ /^(STRAIGHT_FEED|STRAIGHT_TRAVERSE|ARC_FEED|DWELL)\(/) last = n
    }
    END {
      for (i = 1; i <= last; i++) print line[i]
      m = 0
      for (i = last + 1; i <= n; i++) {
        if (line[i] ~ /^(SET_FEED_MODE|SET_FEED_RATE)\(/ || (line[i] in seen)) continue
        seen[line[i]] = 1
        for (j = ++m; j > 1 && tail[j - 1] > line[i]; j--) tail[j] = tail[j - 1]
        tail[j] = line[i]
      }
      for (j = 1; j <= m; j++) print tail[j]
    }'
}

t_init oracle
for ngc in "$here"/*.ngc; do
  name=$(basename "$ngc" .ngc)
  t_case "$name"
  prog=$progs/$name.u22
  if [ ! -f "$prog" ]; then
    bad "no programs/2u22/$name.u22 for the twin"
    continue
  fi
  if ! rs274 -g "$ngc" >"$T/$name.raw" 2>"$T/$name.rs274err"; then
    bad "rs274 failed" "$(tail -n 3 "$T/$name.rs274err")"
    continue
  fi
  canon_filter <"$T/$name.raw" >"$T/$name.want"
  set -- run "$prog" --dialect 2u22 --trace=canon
  [ -f "$progs/$name.operator" ] && set -- "$@" --operator "$progs/$name.operator"
  "$s42" "$@" >"$T/$name.s42raw" 2>"$T/$name.s42err"
  st=$?
  if [ "$st" -ne 0 ]; then
    bad "s42 run exited $st" "$(tail -n 3 "$T/$name.s42err")"
    continue
  fi
  canon_filter <"$T/$name.s42raw" >"$T/$name.got"
  if diff -u "$T/$name.want" "$T/$name.got" >"$T/$name.diff"; then
    echo "ok   $name ($(wc -l <"$T/$name.want") calls)"
    ok
  else
    bad "s42's canon differs from rs274's (--- rs274, +++ s42)" "$(head -n 40 "$T/$name.diff")"
  fi
done
t_case ""
t_done
