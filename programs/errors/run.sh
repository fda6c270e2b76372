#!/bin/sh
# programs/errors/: one program for each error class, each with NAME.expect,
# the transcript of the commands that show it.  For every NAME.expect this
# runs its commands, in order, in a fresh scratch copy of this folder, and
# compares:
#   $ COMMAND            a shell command; `s42` is the binary under test, and
#                        alone/s42 a copy of it away from its build tree
#   LINES                the exact stderr of the command
#   ? exit N [dump STATUS [CODE]]
#                        its exit status; with `dump`, stdout is the --dump
#                        object, with that "status" and error "code";
#                        without it, stdout must be empty
# Lines starting with # are comments; `@PLUGINDIR@` in an expected line is
# the installed plugin directory that s42 searches last.  The last
# command's stderr must name the code of the file's name (e-array-plus.kp:
# E-ARRAY+), and every code of vm/errors.h must have its program (NAME.kp,
# or NAME.u22 for a code only the 2У22's lathe raises), except those in
# PENDING.
#   sh programs/errors/run.sh ./s42
S42=$(cd "$(dirname "${1:-./s42}")" && pwd)/$(basename "${1:-./s42}")
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
PENDING=""                # every code has its program
tmp=$(mktemp -d "${TMPDIR:-/tmp}/dg-errors.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' INT TERM HUP
export LC_ALL=C.UTF-8 S42
unset S42_PLUGIN_PATH
pass=0 fail=0 skip=0

# code_of NAME: e-array-plus -> E-ARRAY+
code_of() {
  echo "$1" | tr 'a-z' 'A-Z' | sed 's/-PLUS$/+/; s/-MINUS$/-/'
}

# run_cmd DIR CMD: run one transcript command in DIR, stdout and stderr to
# $tmp/out and $tmp/err, its status in $st
run_cmd() {
  (cd "$1" && sh -c 's42() { "$S42" "$@"; }
'"$2") < /dev/null > "$tmp/out" 2> "$tmp/err"
  st=$?
}

# check_one NAME: run NAME.expect; prints FAIL lines, returns 1 on failure
check_one() {
  name=$1
  dir=$tmp/$name
  rm -rf "$dir"
  mkdir -p "$dir/alone"
  cp "$HERE"/*.kp "$dir/"
  cp "$HERE"/*.u22 "$dir/" 2>/dev/null
  cp "$HERE"/*.operator "$HERE"/*.tool "$HERE"/*.machine "$dir/" 2>/dev/null
  cp "$S42" "$dir/alone/s42"
  plugindir=$(cd "$dir" && alone/s42 plugins 2>/dev/null | sed -n 's/.*searched: //p')
  if grep -q '^\$ alone/s42' "$HERE/$name.expect"; then
    if ! (cd "$dir" && alone/s42 plugins 2>/dev/null | grep -q '^no plugins found'); then
      echo "errors: $name skipped: a copy of s42 away from its build tree still finds plugins in $plugindir (installed?)"
      return 2
    fi
  fi
  ok=0 cmd="" ncmd=0 last_err=""
  : > "$tmp/want"
  while IFS= read -r line || [ -n "$line" ]; do
    case $line in
      '$ '*)
        cmd=${line#'$ '}
        : > "$tmp/want"
        ;;
      '? '*)
        if [ -z "$cmd" ]; then echo "FAIL errors $name: '?' without a command"; return 1; fi
        ncmd=$((ncmd + 1))
        run_cmd "$dir" "$cmd"
        set -- ${line#'? '}
        if [ "$1" != exit ]; then echo "FAIL errors $name: bad line: $line"; return 1; fi
        want_st=$2
        if [ "$st" != "$want_st" ]; then
          echo "FAIL errors $name: \`$cmd\`: exit status $st, expected $want_st"
          sed 's/^/    | /' "$tmp/err"
          ok=1
        fi
        if ! cmp -s "$tmp/want" "$tmp/err"; then
          echo "FAIL errors $name: \`$cmd\`: stderr differs (- expected, + got):"
          diff "$tmp/want" "$tmp/err" | sed -n 's/^</    -/p; s/^>/    +/p'
          ok=1
        fi
        if [ "$3" = dump ]; then
          if ! python3 - "$tmp/out" "$4" "$5" <<'EOF'
import json, sys
path, status, code = sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else ""
try:
    d = json.load(open(path, encoding="utf-8"))
except ValueError as e:
    print("    stdout is not one JSON object: %s" % e)
    sys.exit(1)
got = (d.get("error") or {}).get("code", "")
if d.get("status") != status or got != code:
    print("    dump: status %r, error code %r; expected %r, %r" % (d.get("status"), got, status, code))
    sys.exit(1)
EOF
          then
            echo "FAIL errors $name: \`$cmd\`: the dump is not as expected"
            ok=1
          fi
        elif [ -s "$tmp/out" ]; then
          echo "FAIL errors $name: \`$cmd\`: unexpected stdout:"
          head -5 "$tmp/out" | sed 's/^/    | /'
          ok=1
        fi
        last_err=$(cat "$tmp/err")
        cmd=""
        ;;
      '#'*) ;;
      *)
        if [ -n "$cmd" ]; then
          printf '%s\n' "$line" | sed "s|@PLUGINDIR@|$plugindir|g" >> "$tmp/want"
        elif [ -n "$line" ]; then
          echo "FAIL errors $name: a line outside a command: $line"
          return 1
        fi
        ;;
    esac
  done < "$HERE/$name.expect"
  if [ -n "$cmd" ]; then echo "FAIL errors $name: \`$cmd\` has no '? exit' line"; return 1; fi
  if [ $ncmd -eq 0 ]; then echo "FAIL errors $name: no command"; return 1; fi
  code=$(code_of "$name")
  case $last_err in
    *"[$code]"*) ;;
    *) echo "FAIL errors $name: the last command does not report [$code]"; ok=1 ;;
  esac
  return $ok
}

for kp in "$HERE"/*.kp "$HERE"/*.u22; do
  [ -f "$kp" ] || continue
  name=$(basename "$kp"); name=${name%.*}
  if [ ! -f "$HERE/$name.expect" ]; then
    echo "FAIL errors $name: no $name.expect"
    fail=$((fail + 1))
    continue
  fi
  check_one "$name"
  case $? in
    0) pass=$((pass + 1)) ;;
    2) skip=$((skip + 1)) ;;
    *) fail=$((fail + 1)) ;;
  esac
done
for e in "$HERE"/*.expect; do
  [ -f "${e%.expect}.kp" ] || [ -f "${e%.expect}.u22" ] ||
    { echo "FAIL errors: $(basename "$e") has no program"; fail=$((fail + 1)); }
done

# every error class of vm/errors.h has its program (or is pending)
for code in $(sed -n 's/^ *ERR([A-Z0-9]*, *"\(E-[A-Z0-9+-]*\)".*/\1/p' "$ROOT/vm/errors.h"); do
  f=$(echo "$code" | tr 'A-Z' 'a-z' | sed 's/+$/-plus/; s/\(.\)-$/\1-minus/')
  if [ -f "$HERE/$f.kp" ] || [ -f "$HERE/$f.u22" ]; then continue; fi
  case " $PENDING " in
    *" $code "*) echo "errors: $code has no program yet (pending: the tooth-search work)" ;;
    *) echo "FAIL errors: $code has no program ($f.kp)"; fail=$((fail + 1)) ;;
  esac
done

echo "errors: $pass passed, $fail failed${skip:+, $skip skipped}" | sed 's/, 0 skipped$//'
[ $fail -eq 0 ]
