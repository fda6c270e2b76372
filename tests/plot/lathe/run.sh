#!/bin/sh
# The plot engine's lathe view (src/host/plot_lathe.c): pictures of canonical calls checked
# with lcheck.py -- the removed material and the part where the calls cut,
# the arcs' sense against hand-computed points, the cut past the stock's
# end in red and named, the caption's status, stock and warnings in the
# PDF's text and the SVG's <title>/<desc>, "no moves" for no calls, and
# the refusals (an unknown extension, a missing directory).  The calls come
# from a small driver (driver.c, built here from the engine's sources); the
# picture `s42 plot` makes of fig1_9.u22 with --stock is checked too.
#   sh tests/plot/lathe/run.sh ./s42
S42=${1:-./s42}
PY=${PYTHON:-python3}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../../.." && pwd)
LSAN_OPTIONS="suppressions=$HERE/../lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export LSAN_OPTIONS
. "$HERE/../../lib.sh"
t_init plot-lathe
fail() { t_case "$1"; shift; bad "$@"; t_case ""; }

DRV=$T/driver
if ! ${CC:-cc} -O1 -g -I"$ROOT/src/host" -I"$ROOT/src/core" -I"$ROOT/vm" $(pkg-config --cflags cairo) -o "$DRV" \
     "$HERE/driver.c" "$ROOT/src/host/plot.c" "$ROOT/src/host/plot_lathe.c" "$ROOT/src/host/plot_planes.c" \
     "$ROOT/src/host/picture.c" "$ROOT/src/host/cairo_dl.c" "$ROOT/src/core/geom.c" \
     "$ROOT/src/core/atomic.c" \
     -lm -ldl 2>"$T/cc.err"; then
  fail build "the driver does not build" "$(cat "$T/cc.err")"
  t_done
fi

# pic NAME CALLS [driver options]: NAME.png .svg .pdf, the points in NAME.xy
pic() {
  name=$1 calls=$2
  shift 2
  for ext in png svg pdf; do
    if ! "$DRV" "$HERE/$calls" "$T/$name.$ext" "$@" >"$T/$name.xy" 2>"$T/$name.err"; then
      fail "$name" "the driver failed for .$ext" "$(cat "$T/$name.err")"
      return 1
    fi
  done
}
# px NAME CHECK...: the PNG's pixels
px() {
  name=$1
  shift
  if msg=$(XY="$T/$name.xy" "$PY" "$HERE/lcheck.py" "$T/$name.png" "$@"); then ok; else fail "$name" "$msg"; fi
}
# text NAME TEXT...: in the PDF's text and the SVG's title and desc
text() {
  name=$1
  shift
  for ext in pdf svg; do
    if msg=$("$PY" "$HERE/lcheck.py" --text "$T/$name.$ext" "$@"); then ok; else fail "$name" "$msg"; fi
  done
}

# Fig. 1.9: turned Ø34 over Z -2 .. -30 and Ø38 to -50 from a bar Ø40
if pic fig19 fig19.calls --stock 40x100 --xy 18.5 -15 --xy 8 -15 --xy 18 -70 --xy 19.4 -40 --xy 5 -80; then
  px fig19 removed@18.5,-15 part@8,-15 part@18,-70 !removed@18,-70 removed@19.4,-40 part@5,-80 !red@5,-80
  text fig19 fig19.calls "end" "stock Ø40 × 100 mm, face at Z 0" "path: max Ø100.00, Z -50.00 .. 200.00" "15 moves"
fi

# a shaft: shoulders, arcs, a groove, a thread, a pass into the chuck side
if pic shaft shaft.calls --stock 40x100 --xy 19 -101 --xy 19 -80 --xy 14 -45 --xy 18 -65 --xy 6 -50; then
  px shaft red@19,-101 !red@19,-80 removed@14,-45 part@18,-65 part@6,-50
  text shaft "cuts into the chuck side at Z -102.00" "the tool reached the axis at Z -0.50" "cut off"
  if grep -q '^chuck -102.000$' "$T/shaft.xy"; then ok; else fail shaft "plot_lathe_chuck: $(cat "$T/shaft.xy")"; fi
fi

# the arcs' sense: the middles computed by hand, not their mirror points
if pic arcs arcs.calls --xy 17.071 -2.929 --xy 2.929 -17.071 --xy 12.929 -37.071 --xy 27.071 -22.929; then
  px arcs feed@17.071,-2.929 !feed@2.929,-17.071 feed@12.929,-37.071 !feed@27.071,-22.929
  text arcs "no stock given"
fi

# a run that failed, and a path that never touches the stock
if pic status status.calls --stock 10x5; then
  text status "stopped: E-ARC at N12" "the path never touches the stock"
fi

# no calls at all: a picture that says so
if pic empty empty.calls --stock 40x100; then
  text empty "no moves" "run not finished"
fi

# an unknown extension: refused with the formats named, no file
if ! "$DRV" "$HERE/fig19.calls" "$T/out.jpg" 2>"$T/jpg.err" && grep -q '\.png' "$T/jpg.err" && [ ! -e "$T/out.jpg" ]; then
  ok
else
  fail extension "a .jpg was not refused with a message naming .png" "$(cat "$T/jpg.err")"
fi
# a directory that does not exist: refused, nothing left behind
if ! "$DRV" "$HERE/fig19.calls" "$T/nodir/out.png" 2>"$T/nodir.err" && grep -q 'nodir' "$T/nodir.err"; then
  ok
else
  fail nodir "a missing directory was not refused" "$(cat "$T/nodir.err")"
fi
if [ "$(ls "$T" | grep -c '\.tmp')" -eq 0 ]; then ok; else fail tmp "temporary files left: $(ls "$T")"; fi

# the host, once `s42 plot` runs 2У22 programs with --stock
if "$S42" plot "$HERE/fig1_9.u22" -o "$T/host.pdf" --stock 40x100 >/dev/null 2>"$T/host.err"; then
  "$S42" plot "$HERE/fig1_9.u22" -o "$T/host.png" --stock 40x100 >/dev/null 2>>"$T/host.err"
  if [ "$(od -An -c -N4 "$T/host.png" | tr -d ' ')" = '211PNG' ]; then ok; else fail host "no PNG" "$(cat "$T/host.err")"; fi
  "$S42" plot "$HERE/fig1_9.u22" -o "$T/host.svg" --stock 40x100 >/dev/null 2>>"$T/host.err"
  text host "fig1_9.u22" "end" "stock Ø40 × 100 mm" "path: max Ø100.00, Z -50.00 .. 200.00"
else
  echo "plot-lathe: note: $S42 does not plot fig1_9.u22 with --stock yet (not checked)"
fi

t_done
