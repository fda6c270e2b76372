#!/bin/sh
# The README's probe image and its annotated twin, as --dump-images writes
# them: the seed's G10 D1+60000 M10 on docs/toothsearch/seed-reamer-400.tool,
# section 1, the first of the four shots of the revolution.
#   sh docs/toothsearch/README-images.sh [./s42]
set -e
S42=${1:-./s42}
d=$(mktemp -d "${TMPDIR:-/tmp}/tg-readme-img.XXXXXX")
trap 'rm -rf "$d"' EXIT
printf '№1 R0+0 ^\n№10 G10 D1+60000 M10 ^\n№11 M02 ^\n' > "$d/seed.kp"
printf 'key PUSK\nsection X +30000 A -43200\nkey PUSK\nkey PS\nkey PUSK\n' > "$d/seed.op"
"$S42" run "$d/seed.kp" --tool docs/toothsearch/seed-reamer-400.tool --operator "$d/seed.op" --dump-images "$d/img"
cp "$d/img/N10_section1_shot1.png" docs/toothsearch/probe.png
cp "$d/img/N10_section1_shot1_annotated.png" docs/toothsearch/probe-annotated.png
ls -l docs/toothsearch/*.png
