#!/bin/sh
# The tooth-search plugin through s42 run, against the truth of the tool
# models: for each model a G10/G11 block (with M10, or without) runs with an
# operator script that follows the flute to section 2; the dump's R99,
# array 2, TK and UG are compared with the model (steps ±0.03°, TK ±0.5 %,
# UG ±0.03°, tooth count exact, array 2 summing to 360° when it holds every
# step).  Then --dump-images (the PNGs, plain and annotated), --lang en, and
# the search's time at the default speed and with M12.
#   sh tests/toothsearch/plugin.sh ./s42
S42=${1:-./s42}
PY=${PYTHON:-python3}
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/../lib.sh"
t_init "toothsearch plugin"

# model G M10 SECTION_X: the program, the operator script, the run, the check
search() {
  tool=$HERE/$1
  g=$2
  m10=$3
  dx=$4
  name=$(basename "$1" .tool)-$g-$m10
  printf '; %s\n№1 R99+0 ^\n№10 %s D1+%s %s ^\n№11 M02 ^\n' "$name" "$g" \
    "$("$PY" "$HERE/truth.py" diameter "$tool")" "$([ "$m10" = M10 ] && echo M10)" > "$T/$name.kp"
  if [ "$m10" = M10 ]; then
    # the operator follows the flute: A turns with the helix over dx
    turn=$("$PY" "$HERE/truth.py" turn "$tool" "$dx")
    printf 'key PUSK\nsection X %+d A %+d\nkey PUSK\nkey PS\nkey PUSK\n' "$dx" "$turn" > "$T/$name.op"
  else
    printf 'key PUSK\nkey PS\nkey PUSK\n' > "$T/$name.op"
  fi
  "$S42" run "$T/$name.kp" --tool "$tool" --operator "$T/$name.op" --dump > "$T/$name.dump" 2> "$T/$name.err"
  st=$?
  if [ $st -ne 0 ]; then
    bad "$name: exit $st: $(cat "$T/$name.err")"
    return
  fi
  if msg=$("$PY" "$HERE/truth.py" check "$tool" "$T/$name.dump" "$g" "$m10" 2>&1); then
    ok
    echo "ok   $name  $msg"
  else
    bad "$name: $msg"
  fi
}

search t004_reamer_seed.tool G10 M10 30000
search t004_reamer_seed.tool G10 none 0
search t010_left.tool G11 M10 -25000
search t024_uneven_right.tool G10 M10 40000
search t003_endmill_left.tool G11 none 0
search t018_uneven_left.tool G11 M10 20000
search t008_straight_uneven.tool G10 M10 30000
search t150_uneven_left.tool G11 none 0

# --dump-images: both sections, four shots each, plain and annotated
printf '№1 R0+1 ^\n№10 G10 D1+60000 M10 ^\n№11 M02 ^\n' > "$T/seed.kp"
printf 'key PUSK\nsection X +30000 A -43200\nkey PUSK\nkey PS\nkey PUSK\n' > "$T/seed.op"
"$S42" run "$T/seed.kp" --tool "$HERE/t004_reamer_seed.tool" --operator "$T/seed.op" \
  --dump-images "$T/img" > /dev/null 2> "$T/img.err"
st=$?
if [ $st -eq 0 ] && msg=$("$PY" "$HERE/truth.py" images "$T/img" 768 N10_section1 N10_section2); then ok; else
  bad "--dump-images: exit $st: ${msg:-} $(cat "$T/img.err")"
fi
# without M10 the second revolution is section1_search2
printf '№1 R0+1 ^\n№10 G10 D1+60000 ^\n№11 M02 ^\n' > "$T/nom10.kp"
printf 'key PUSK\nkey PS\nkey PUSK\n' > "$T/nom10.op"
"$S42" run "$T/nom10.kp" --tool "$HERE/t004_reamer_seed.tool" --operator "$T/nom10.op" \
  --dump-images "$T/img2" > /dev/null 2> "$T/img2.err"
if msg=$("$PY" "$HERE/truth.py" images "$T/img2" 768 N10_section1 N10_section1_search2); then ok; else
  bad "--dump-images without M10: $msg $(cat "$T/img2.err")"
fi
# a --dump-images that cannot be a directory: bad usage before the run
: > "$T/afile"
"$S42" run "$T/seed.kp" --tool "$HERE/t004_reamer_seed.tool" --operator "$T/seed.op" \
  --dump-images "$T/afile" > /dev/null 2> "$T/bad.err"
st=$?
if [ $st -eq 2 ] && grep -q "dump-images $T/afile: not a directory" "$T/bad.err"; then ok; else
  bad "--dump-images on a file: exit $st: $(cat "$T/bad.err")"
fi

# --lang en: the directive and P5 in English
printf 'key PUSK\n' > "$T/one.op"
"$S42" run "$T/seed.kp" --tool "$HERE/t004_reamer_seed.tool" --operator "$T/one.op" --lang en --screen \
  > "$T/en.out" 2> /dev/null
if grep -q "^MANUAL" "$T/en.out" && grep -q "probe into section 2" "$T/en.out"; then ok; else
  bad "--lang en at section 2: $(cat "$T/en.out")"
fi
"$S42" run "$T/seed.kp" --tool "$HERE/t004_reamer_seed.tool" --operator "$T/seed.op" --lang en --screen \
  > "$T/en2.out" 2> /dev/null
if grep -q "^TEETH  *4$" "$T/en2.out" && grep -q "^HAND  *RIGHT$" "$T/en2.out"; then ok; else
  bad "--lang en P5: $(cat "$T/en2.out")"
fi

# the text trace names the search's results on its row
"$S42" run "$T/seed.kp" --tool "$HERE/t004_reamer_seed.tool" --operator "$T/seed.op" --trace > "$T/trace" 2>/dev/null
if grep -q "N10 .*G10 .*search={teeth=4 tk=2[45][0-9]* ug=370[0-9]* hand=right mismatch=false} jogs X+30000 Y+0 Z+0 A-43200  t 21.6000" "$T/trace"; then
  ok
else
  bad "trace row of the search: $(cat "$T/trace")"
fi

t_done
