# tests/lib.sh: what the shell harnesses share.  POSIX sh (they run under
# /bin/sh, which is dash here); every name it defines starts with t_ or T_,
# except ok and bad.  A harness sources it first:
#
#   . "$(dirname "$0")/../lib.sh"
#   t_init NAME
#   ... ok / bad "what went wrong" ...
#   t_done
#
#   t_init NAME      T: a new directory under $TMPDIR (or /tmp), removed at
#                    exit; INT, TERM and HUP exit 1 (through the same cleanup)
#   ok               one check passed
#   bad MSG [LINE...]  one check failed: prints "FAIL NAME: MSG" ("FAIL NAME
#                    CASE: MSG" after t_case CASE), then each LINE indented by
#                    two spaces, then calls t_on_bad (a harness may redefine
#                    it, e.g. to show the terminal's screen)
#   t_case CASE      name the case that later FAIL lines are about ("" none)
#   t_check MSG CMD...  ok when CMD succeeds, bad MSG otherwise
#   t_done [TAIL]    prints "NAME: N passed, M failed[TAIL]" (other tooling
#                    greps that line) and exits: 1 after a failure, else 0
#   t_atexit CMD     run the shell command CMD at exit, before T is removed
#                    (the last one registered runs first)
#   t_wait SECONDS CMD...  run CMD every 0.1 s until it succeeds (status 0)
#                    or SECONDS (a whole number) have gone (status 1); the
#                    limit counts polls, so a loaded machine waits longer,
#                    never less
#   t_port           prints a TCP port on 127.0.0.1 that was free a moment
#                    ago (the kernel's choice; a server that then finds it in
#                    use should try another)
#   t_ms             prints a clock in milliseconds
#   t_stop PID [SECONDS]  SIGTERM, and SIGKILL after SECONDS (5) if it is
#                    still there; sets T_STATUS to its exit status
#   t_fast_dir       sets T_FAST to a new directory on a tmpfs (in /dev/shm
#                    when it is there and writable; removed at exit), else
#                    to T: for the tests whose many fsyncs would otherwise
#                    wait on the disk
#   t_have CMD       CMD is installed

# python3, found once: through a version manager's shim (pyenv's is a bash
# script that runs `pyenv exec`) every call costs some 70 ms more, and the
# harnesses call it a few hundred times; where python3 is the interpreter
# itself this changes nothing
if T_PY=$(python3 -c 'import sys; print(sys.executable)' 2>/dev/null) && [ -x "$T_PY" ]; then
  python3() { "$T_PY" "$@"; }
fi

T_NAME=
T_CASE=
T_PASS=0
T_FAIL=0
T=
T_ATEXIT=:

t_cleanup_() {
  eval "$T_ATEXIT"
  [ -n "$T" ] && rm -rf "$T"
}

t_init() {
  T_NAME=$1
  T_PASS=0
  T_FAIL=0
  T=$(mktemp -d "${TMPDIR:-/tmp}/s42-$(echo "$1" | tr ' /' '--').XXXXXX") || {
    echo "FAIL $1: cannot make a temporary directory in ${TMPDIR:-/tmp}"
    exit 1
  }
  trap t_cleanup_ EXIT
  trap 'exit 1' INT TERM HUP
}

t_atexit() {
  T_ATEXIT="$1
$T_ATEXIT"
}

ok() { T_PASS=$((T_PASS + 1)); }

t_on_bad() { :; }

bad() {
  T_FAIL=$((T_FAIL + 1))
  echo "FAIL $T_NAME${T_CASE:+ $T_CASE}: $1"
  shift
  [ $# -gt 0 ] && printf '%s\n' "$@" | sed 's/^/  /'
  t_on_bad
  return 0
}

t_case() { T_CASE=$1; }

t_check() {
  t_msg_=$1
  shift
  if "$@"; then ok; else bad "$t_msg_"; fi
}

t_done() {
  echo "$T_NAME: $T_PASS passed, $T_FAIL failed${1:-}"
  [ "$T_FAIL" -eq 0 ] && exit 0
  exit 1
}

t_wait() {
  t_lim_=$(($1 * 10))
  shift
  t_n_=0
  while [ "$t_n_" -lt "$t_lim_" ]; do
    "$@" && return 0
    sleep 0.1
    t_n_=$((t_n_ + 1))
  done
  "$@"
}

t_port() {
  python3 -c 'import socket
s = socket.socket()
s.bind(("127.0.0.1", 0))
print(s.getsockname()[1])' 2>/dev/null || echo $((20000 + $(od -An -N2 -tu2 /dev/urandom) % 40000))
}

t_ms() { date +%s%3N; }

t_stop() {
  kill -TERM "$1" 2>/dev/null
  ( sleep "${2:-5}"; kill -KILL "$1" ) >/dev/null 2>&1 &
  t_wd_=$!
  wait "$1"
  T_STATUS=$?
  kill "$t_wd_" 2>/dev/null
  wait "$t_wd_" 2>/dev/null
  return 0
}

t_fast_dir() {
  if [ -d /dev/shm ] && [ -w /dev/shm ] && T_FAST=$(mktemp -d "/dev/shm/${T##*/}.XXXXXX" 2>/dev/null); then
    t_atexit "rm -rf '$T_FAST'"
  else
    T_FAST=$T
  fi
}

t_have() { command -v "$1" >/dev/null 2>&1; }
