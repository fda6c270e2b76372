#!/bin/sh
# Limits and bad input (README "Limits and bad input"): each must end with a
# clear message and its exit status, never a crash.  Run by make check, and
# under make asan with the sanitized binary.   usage: run.sh S42
S42=${1:-./s42}
. "$(dirname "$0")/../lib.sh"
t_init limits
t_fast_dir                                     # T_FAST: the M15 saves of loop.kp, on a tmpfs
# fail NAME MSG: "FAIL limits NAME: MSG", then the first lines of stderr
fail() { t_case "$1"; bad "$2" "$(head -5 "$T/err")"; t_case ""; }

# expect NAME STATUS PATTERN FILE [ARGS...]: s42 run FILE ARGS exits with
# STATUS and says PATTERN (grep -E) on stderr
expect() {
  name=$1 want=$2 pat=$3 f=$4
  shift 4
  "$S42" run "$f" "$@" >"$T/out" 2>"$T/err"
  st=$?
  if [ "$st" -ne "$want" ]; then
    fail "$name" "status $st, expected $want"
  elif ! grep -Eq -- "$pat" "$T/err"; then
    fail "$name" "stderr does not match /$pat/"
  else
    ok
  fi
}

# nesting 10,000 deep: parentheses, signs, functions, a condition
python3 - "$T" <<'PY'
import sys
d = sys.argv[1]
def w(name, text, mode="w"):
    with open(d + "/" + name, mode) as f:
        f.write(text)
n = 10000
w("parens.kp", "№1 R1+" + "(" * n + "1" + ")" * n + " ^\n№2 M02 ^\n")
w("signs.kp", "№1 R1+" + "-" * n + "1 ^\n№2 M02 ^\n")
w("funcs.kp", "№1 R1+" + "SI(" * n + "1" + ")" * n + " ^\n№2 M02 ^\n")
w("cond.kp", "№1 P" + "(" * n + "R1:R:1" + ")" * n + "2 ^\n№2 M02 ^\n")
# a block of a million characters on one line
w("longblock.kp", "№1 R1+" + "1+" * 500000 + "1 ^\n№2 M02 ^\n")
# bytes that are not UTF-8, a NUL byte, both inside text
w("badutf8.kp", b"\xe2\x84\x961 R1+1 \xff\xfe ^\n\xe2\x84\x962 M02 ^\n", "wb")
w("nul.kp", b"\xe2\x84\x961 R1+\x00 ^\n\xe2\x84\x962 M02 ^\n", "wb")
w("textbad.kp", "№1 G33 /ОК\udcff/ ^\n№2 M02 ^\n".encode("utf-8", "surrogateescape"), "wb")
cyr = "; програма свердління\nN1 G33 /СВЕРДЛО/ ^\nN2 G27 /ДІАМЕТР/ ^\nN3 G28 /1:9/ R1 ^\nN4 M02 ^\n"
w("cp1251.kp", cyr.encode("cp1251"), "wb")
w("koi8.kp", cyr.encode("koi8_u"), "wb")
w("cp866.kp", cyr.replace("і", "i").replace("І", "I").encode("cp866"), "wb")
w("textnul.kp", "№1 G33 /ОК\0/ ^\n№2 M02 ^\n")
# an empty file, and one with only comments and blank blocks
w("empty.kp", "")
w("comments.kp", "; nothing here\n\n ^ ^\n")
# an operator script over 1 MiB
w("big.op", "key PUSK\n" * 120000)
PY

expect deep-parentheses 1 'parens\.kp:1:[0-9]+: error: N1: expression nested too deeply \[E-SYNTAX\]' "$T/parens.kp"
expect deep-signs 1 'signs\.kp:1:[0-9]+: error: N1: .*nested too deeply \[E-SYNTAX\]' "$T/signs.kp"
expect deep-functions 1 'funcs\.kp:1:[0-9]+: error: N1: .*nested too deeply \[E-SYNTAX\]' "$T/funcs.kp"
expect deep-condition 1 'cond\.kp:1:[0-9]+: error: N1: .*nested too deeply \[E-SYNTAX\]' "$T/cond.kp"
expect long-block 1 'longblock\.kp:1:[0-9]+: error: N1: .*\[E-BLOCKLEN\]' "$T/longblock.kp"
# more blocks than the limit (16,777,216: BLOCK's 24-bit operand): 100 MB,
# 2 GB and a few seconds to compile, too much under a sanitizer's memory
if [ -n "$ASAN_OPTIONS" ] || ldd "$S42" 2>/dev/null | grep -q libasan; then
  echo "limits: a sanitizer build: the 16,777,217-block program was skipped"
else
  python3 -c 'import sys; open(sys.argv[1], "w").write("№1 M03 ^\n" + "M03 ^\n" * 16777216 + "M02 ^\n")' "$T/blocks.kp"
  expect too-many-blocks 1 'blocks\.kp:16777217:1: error: N-: more than 16777216 blocks: the program is too long \[E-LIMIT\]' "$T/blocks.kp"
  rm -f "$T/blocks.kp"
fi
expect non-utf8 1 'badutf8\.kp:1:9: error: N-: not UTF-8: the byte 0xFF here is no character; a program is UTF-8 text \[E-SYNTAX\]$' "$T/badutf8.kp"
expect nul-byte 1 'nul\.kp:1:7: error: N1: expected a number, parameter or function, found character 0x00 \[E-SYNTAX\]' "$T/nul.kp"
expect text-non-utf8 1 'textbad\.kp:1:11: error: N-: not UTF-8: the byte 0xFF here is no character' "$T/textbad.kp"
# a whole file in an 8-bit Cyrillic encoding: one error, and the iconv command
for e in cp1251:cp1251 koi8:koi8-u cp866:cp866; do
  expect "encoding-${e%%:*}" 1 "${e%%:*}\\.kp:1:3: error: N-: not UTF-8 \\(it reads as ${e#*:}.*\\): convert it with \`iconv -f ${e#*:} -t utf-8 .*${e%%:*}\\.kp > NEW\\.kp\`" "$T/${e%%:*}.kp"
  if [ "$(grep -c 'error:' "$T/err")" -ne 1 ] || [ "$(wc -l <"$T/err")" -ne 1 ]; then
    t_case "encoding-${e%%:*}"; bad "more than one line: $(cat "$T/err")"; t_case ""
  fi
done
expect text-nul 1 'textnul\.kp:1:11: error: N1: G33: text holds a NUL byte \[E-TEXT\]' "$T/textnul.kp"
expect empty-file 1 'empty\.kp:1:1: error: N-: the program is empty: it needs block 1 and M2 \[E-SUB\]' "$T/empty.kp"
expect only-comments 1 'comments\.kp:1:1: error: N-: the program is empty' "$T/comments.kp"
expect directory 4 "s42: $T: is a directory, not a file" "$T"
expect missing-file 4 'no-such\.kp: No such file or directory' "$T/no-such.kp"
# a program file over 512 MiB (sparse: nothing is written)
truncate -s 513M "$T/huge.kp"
expect file-size 4 'huge\.kp: too large: at most 536870912 bytes are read \[E-LIMIT\]' "$T/huge.kp"
rm -f "$T/huge.kp"
expect operator-size 4 'big\.op: too large: at most 1048576 bytes are read \[E-LIMIT\]' programs/drill_dialog.kp \
  --operator "$T/big.op"

# a FIFO, a device: refused at once, never waited on (timeout 20: status 124
# would be a hang); a pipe on standard input is read
mkfifo "$T/fifo"
expect_t() {
  name=$1
  shift
  timeout 20 "$@" >"$T/out" 2>"$T/err" </dev/null
  echo $? > "$T/st"
}
chk() {   # NAME STATUS PATTERN: of the last expect_t
  st=$(cat "$T/st")
  if [ "$st" -ne "$2" ]; then
    fail "$1" "status $st, expected $2"
  elif ! grep -Eq -- "$3" "$T/err"; then
    fail "$1" "stderr does not match /$3/"
  else
    ok
  fi
}
fifo_msg='fifo: is a FIFO, not a regular file \(a pipe is read only as standard input\)'
expect_t fifo-program "$S42" run "$T/fifo"; chk fifo-program 4 "s42: $T/$fifo_msg"
expect_t fifo-check "$S42" check "$T/fifo"; chk fifo-check 4 "s42: $T/$fifo_msg"
expect_t fifo-operator "$S42" run programs/drill_dialog.kp --operator "$T/fifo"; chk fifo-operator 4 "$fifo_msg"
expect_t fifo-tool "$S42" run programs/drill_dialog.kp --tool "$T/fifo"; chk fifo-tool 2 "s42: --tool $T/$fifo_msg"
expect_t fifo-state-restart "$S42" run tests/restart/loop.kp --restart --state "$T/fifo" --dump
chk fifo-state-restart 1 "restart refused: no restart state: $T/fifo: is a FIFO, not a regular file \[E-STATE\]"
expect_t fifo-state-save "$S42" run tests/restart/loop.kp --state "$T/fifo" --dump
chk fifo-state-save 4 "error: N3: cannot save the M15 restart state: $T/fifo is a FIFO, not a restart state: it is not replaced \[E-STATE\]"
[ -p "$T/fifo" ] && ok || fail fifo-state-save "the FIFO was replaced"
expect_t device-program "$S42" run /dev/zero; chk device-program 4 's42: /dev/zero: is a character device, not a regular file'
expect_t device-operator "$S42" run programs/drill_dialog.kp --operator /dev/null
chk device-operator 4 's42: /dev/null: is a character device, not a regular file'
# standard input as a pipe: the program, and the operator script
if cat programs/drill_point.kp | "$S42" run /dev/stdin --dump 2>"$T/err" | grep -q '"status":"end"'; then
  ok
else
  fail stdin-program "a program on a pipe did not run"
fi
if cat programs/drill_dialog.operator | "$S42" run programs/drill_dialog.kp --operator /dev/stdin --dump 2>"$T/err" |
   grep -q '"status":"end"'; then
  ok
else
  fail stdin-operator "a script on a pipe was not read"
fi

# the operator script: no word cut short, `at` for a block the program has,
# and a warning for each action a run left
op() { printf '%s\n' "$@" > "$T/s.op"; }
op "answer 35000" "answer 95000" "answer 140" "answer 118" "override $(printf %064d 150)"
expect op-long-word 2 "s.op:5:10: error: a word of 64 characters: at most 63 \(it is not read cut short\)" \
  programs/drill_dialog.kp --operator "$T/s.op"
op "at N$(printf %063d 22) key EXIT"              # before: read as at N2
expect op-long-at 2 's.op:1:4: error: a word of 64 characters' programs/drill_dialog.kp --operator "$T/s.op"
op "at N$(printf %062d 2) key STOP"               # 63 characters: read whole
expect op-zeros-at 3 'note: N2: the cycle was stopped \(key STOP\)' tests/restart/loop.kp --operator "$T/s.op" \
  --state "$T_FAST/loop.state"                    # (not beside the program, in the tree)
printf 'answer 35\000000\n' > "$T/s.op"
expect op-nul 2 's.op:1:8: error: a NUL byte inside a word' programs/drill_dialog.kp --operator "$T/s.op"
op "answer 35000" "  at N22 key EXIT"
expect op-at-missing 2 "s.op:2:3: error: at N22: the program has no block N22, so this never fires" \
  programs/drill_dialog.kp --operator "$T/s.op"
grep -q "drill_dialog.kp: note: the operator script $T/s.op is refused: the run does not start" "$T/err" &&
  ok || fail op-at-missing "no note"
op "at N1#5 key EXIT" "override 80" "key PUSK" "key PS"
expect op-unused 0 "s.op:1:1: warning: at N1#5 key EXIT never fired: block N1 started only once" \
  tests/restart/loop.kp --operator "$T/s.op" --state "$T_FAST/loop.state"   # 2000 saves
grep -q "s.op:3:1: warning: key PUSK was not used: the run ended before it" "$T/err" &&
  grep -q "s.op:4:1: warning: key PS was not used: the run ended before it" "$T/err" &&
  ! grep -q "s.op:2:" "$T/err" && ok ||
  { t_case op-unused; bad "the unused actions were not each warned" "$(cat "$T/err")"; t_case ""; }

# CRLF line ends: the same run, to the byte, as the LF original
for f in programs/reamer_rake.kp programs/drill_dialog.kp; do
  b=$(basename "$f" .kp)
  sed 's/$/\r/' "$f" > "$T/$b-crlf.kp"
  op=
  [ -f "programs/$b.operator" ] && op="--operator programs/$b.operator"
  # shellcheck disable=SC2086
  "$S42" run "$f" $op --dump --screen > "$T/lf.out" 2>/dev/null
  # shellcheck disable=SC2086
  "$S42" run "$T/$b-crlf.kp" $op --dump --screen > "$T/crlf.out" 2>/dev/null
  if cmp -s "$T/lf.out" "$T/crlf.out"; then
    ok
  else
    t_case "crlf-$b"; bad "the CRLF file runs differently" "$(diff "$T/lf.out" "$T/crlf.out" | head -5)"; t_case ""
  fi
done

t_done
