#!/bin/sh
# s42 plot: for every programs/*.kp (with programs/NAME.operator and NAME.tool when there
# is one) and the tutorial's cycle draw a PNG, an SVG and a PDF and check them
# with check.py: the PNG's size from its header, path pixels where the run
# moved, nothing where it did not, the SVG well-formed, the PDF's header
# text as the dump says.  Also: the refusal of an unknown extension and of
# an output that is the program, and that a failed plot leaves no file
# behind.
#   sh tests/plot/run.sh ./s42
S42=${1:-./s42}
PY=${PYTHON:-python3}
HERE=$(dirname "$0")
PROGS=${PROGRAMS:-programs}
# under ASan: fontconfig's process-long configuration is not ours
LSAN_OPTIONS="suppressions=$(cd "$HERE" && pwd)/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export LSAN_OPTIONS
. "$HERE/../lib.sh"
t_init plot
# fail CASE MSG [LINE...]: "FAIL plot CASE: MSG" and the lines indented
fail() { t_case "$1"; shift; bad "$@"; t_case ""; }

# case NAME PROGRAM.kp [options]: run it (trace, dump) and plot it to PNG,
# SVG and PDF; the plot's status is the run's (and $expect when set);
# check.py checks the pictures (the line under the title: $title when set)
case_() {
  name=$1
  shift
  set -- "$@" --state "$T/$name.state"    # M15 saves here, not beside the program in the tree
  "$S42" run "$@" --trace=json >"$T/$name.jsonl" 2>/dev/null
  want=$?
  if [ -n "$expect" ] && [ "$want" != "$expect" ]; then
    fail "$name" "the run's exit status is $want, the test expects $expect"
    return
  fi
  "$S42" run "$@" --dump >"$T/$name.dump" 2>/dev/null
  st=
  for ext in png svg pdf; do
    "$S42" plot "$@" -o "$T/$name.$ext" 2>>"$T/$name.err"
    st="$st $?"
  done
  if [ "$st" != " $want $want $want" ]; then
    fail "$name" "plot exit$st (png svg pdf), run exit $want" "$(cat "$T/$name.err")"
    return
  fi
  if [ ! -s "$T/$name.png" ] || [ ! -s "$T/$name.svg" ] || [ ! -s "$T/$name.pdf" ]; then
    fail "$name" "no picture written" "$(cat "$T/$name.err")"
    return
  fi
  if msg=$("$PY" "$HERE/check.py" "$T/$name.png" "$T/$name.svg" "$T/$name.jsonl" "$T/$name.dump" \
           "$T/$name.pdf" ${title:+"$title"}); then
    ok
  else
    fail "$name" "$msg"
  fi
}

for kp in "$PROGS"/*.kp; do
  [ -f "$kp" ] || continue
  name=$(basename "$kp" .kp)
  set -- "$kp"
  [ -f "$PROGS/$name.operator" ] && set -- "$@" --operator "$PROGS/$name.operator"
  [ -f "$PROGS/$name.tool" ] && set -- "$@" --tool "$PROGS/$name.tool"
  case_ "$name" "$@"
done
# the tutorial's cycle: its jump-only blocks (P) count in the header
expect=0 case_ tutorial docs/tutorial/cycle.kp --operator docs/tutorial/cycle.operator

# runs that fail: the status is the run's, the picture is still written, the
# line under the title says how and the stop sign marks where
expect=1; title=
case_ e-div0 programs/errors/e-div0.kp
title='not run: E-SYNTAX at N2 (the program does not compile)'
case_ e-syntax programs/errors/e-syntax.kp
expect=3; title='stopped: the operator script had no action for Пуск (key PUSK) at N4'
case_ no-action docs/tutorial/cycle.kp --operator "$HERE/no-action.operator"
title='stopped (key STOP) at N7'
case_ stop-key docs/tutorial/cycle.kp --operator "$HERE/stop-key.operator"
expect=; title=

# oscillation: the strokes are in the scale (reamer_rake above: 100 mm of X
# while nothing else moves X), A's too, and they turn along the path
case_ osc-a "$HERE/osc-a.kp"
case_ osc-line "$HERE/osc-line.kp"
if msg=$("$PY" "$HERE/check.py" --tips "$T/osc-line.png" XZ 12); then
  ok
else
  fail "osc-tips" "$msg"
fi

# a dense A trace: drawn by the band (a solid core and the edges around it),
# the same picture as the plain stroke but for a level here and there
case_ dense-a "$HERE/dense-a.kp"
S42_PLOT_PLAIN=1 "$S42" plot "$HERE/dense-a.kp" -o "$T/dense-a-plain.png" 2>/dev/null
if msg=$("$PY" "$HERE/check.py" --same "$T/dense-a.png" "$T/dense-a-plain.png" 2); then
  ok
else
  fail "dense-a-plain" "$msg"
fi

# a failed run whose picture cannot be written: 4, and no file
"$S42" plot programs/errors/e-div0.kp -o "$T/nodir/div0.png" 2>"$T/nodir-div0.err"
st=$?
if [ $st -eq 4 ] && [ ! -e "$T/nodir/div0.png" ] && grep -q 'nodir' "$T/nodir-div0.err"; then
  ok
else
  fail "io-error-failed-run" "exit $st for a failed run and a missing directory, want 4" "$(cat "$T/nodir-div0.err")"
fi

# the same picture as PDF
first=$(ls "$PROGS"/*.kp | head -n 1)
name=$(basename "$first" .kp)
set -- "$first"
[ -f "$PROGS/$name.operator" ] && set -- "$first" --operator "$PROGS/$name.operator"
"$S42" plot "$@" -o "$T/out.pdf" 2>/dev/null
if head -c 5 "$T/out.pdf" 2>/dev/null | grep -q '%PDF-' && tail -c 8 "$T/out.pdf" | grep -q '%%EOF'; then
  ok
else
  fail "pdf" "$T/out.pdf is not a PDF"
fi

# an unknown extension: usage error, a clear message, no file
"$S42" plot "$@" -o "$T/out.jpg" 2>"$T/jpg.err"
st=$?
if [ $st -eq 2 ] && grep -q '\.png' "$T/jpg.err" && [ ! -e "$T/out.jpg" ]; then
  ok
else
  fail "extension" "exit $st for .jpg, want 2 with a message naming .png/.svg/.pdf" "$(cat "$T/jpg.err")"
fi

# a directory that does not exist: an I/O error, nothing left behind
"$S42" plot "$@" -o "$T/nodir/out.png" 2>"$T/nodir.err"
st=$?
if [ $st -eq 4 ] && [ -s "$T/nodir.err" ]; then
  ok
else
  fail "io-error" "exit $st for a missing directory, want 4" "$(cat "$T/nodir.err")"
fi

# -o naming the program itself -- the same path, with ./ or d/../ before
# it, absolute, a symbolic or a hard link to it -- is refused before the
# run, with status 2 and a message, by the 2С42's plot and the lathe's
# (.u22, or --dialect 2u22); the program (and the name -o gave) is the
# program still, and no picture or temporary file is left
S42_ABS=$(cd "$(dirname "$S42")" && pwd)/$(basename "$S42")
op=$(pwd)/docs/tutorial/cycle.operator
self_dir() {   # a fresh $T/self: the programs, their links, sub/
  rm -rf "$T/self"
  mkdir "$T/self" "$T/self/sub"
  cp docs/tutorial/cycle.kp "$T/self/cycle.png"
  cp programs/2u22/fig1_9.u22 "$T/self/turn.u22"
  cp programs/2u22/fig1_9.u22 "$T/self/turn.png"
  ln -s cycle.png "$T/self/link.svg"
  ln "$T/self/cycle.png" "$T/self/hard.pdf"
  ln -s turn.u22 "$T/self/turn-link.png"
  ln "$T/self/turn.u22" "$T/self/turn-hard.svg"
}
# refused CASE ORIGINAL OUT PROGRAM [ARG...]: s42 plot PROGRAM ARG... -o OUT
# in a fresh $T/self refuses; PROGRAM and OUT are still ORIGINAL's text
refused() {
  name=$1 orig=$(pwd)/$2 out=$3
  shift 3
  self_dir
  (cd "$T/self" && "$S42_ABS" plot "$@" -o "$out") >/dev/null 2>"$T/self.err"
  st=$?
  kept=unchanged
  (cd "$T/self" && cmp -s "$1" "$orig" && cmp -s "$out" "$orig" && [ -L link.svg ] && [ -L turn-link.png ]) ||
    kept=changed
  if [ $st -eq 2 ] && grep -q "^s42: -o $out is the program .* (the same file)" "$T/self.err" && [ $kept = unchanged ] &&
     ! ls "$T/self" | grep -q '\.tmp'; then
    ok
  else
    fail "$name" "exit $st (want 2 and a message), the program or a link $kept" "$(cat "$T/self.err")"
  fi
}
refused self-same docs/tutorial/cycle.kp cycle.png cycle.png --operator "$op"
refused self-dot-slash docs/tutorial/cycle.kp ./cycle.png cycle.png --operator "$op"
refused self-dot-dot docs/tutorial/cycle.kp sub/../cycle.png cycle.png --operator "$op"
refused self-absolute docs/tutorial/cycle.kp "$T/self/cycle.png" cycle.png --operator "$op"
refused self-symlink docs/tutorial/cycle.kp link.svg cycle.png --operator "$op"
refused self-hard-link docs/tutorial/cycle.kp hard.pdf cycle.png --operator "$op"
refused lathe-same programs/2u22/fig1_9.u22 turn.png turn.png --dialect 2u22
refused lathe-dot-slash programs/2u22/fig1_9.u22 ./turn.png turn.png --dialect 2u22
refused lathe-symlink programs/2u22/fig1_9.u22 turn-link.png turn.u22
refused lathe-hard-link programs/2u22/fig1_9.u22 turn-hard.svg turn.u22
# an output that does not exist yet is written
self_dir
if (cd "$T/self" && "$S42_ABS" plot cycle.png --operator "$op" -o ./new.png) 2>"$T/self.err" && [ -s "$T/self/new.png" ]; then
  ok
else
  fail "self-new" "a new -o beside the program was not written" "$(cat "$T/self.err")"
fi

# an existing picture is replaced whole, and no temporary file is left
printf 'old' >"$T/keep.png"
"$S42" plot "$@" -o "$T/keep.png" 2>/dev/null
left=$(ls "$T" | grep -c '\.tmp' || true)
if [ "$(head -c 4 "$T/keep.png" | od -An -c | tr -d ' ')" = '211PNG' ] && [ "$left" -eq 0 ]; then
  ok
else
  fail "atomic" "keep.png not replaced by a PNG, or $left temporary files left"
fi

t_done
