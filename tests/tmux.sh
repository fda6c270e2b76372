# tests/tmux.sh: the one tmux driver of the terminal tests (tests/tui/run.sh,
# the tutorial's tests/tutorial/tutorial.py, the terminal part of
# tests/modbus/run.sh).  POSIX sh.  A shell harness sources it (after
# tests/lib.sh, whose t_atexit then ends the server at exit):
#
#   . "$(dirname "$0")/../tmux.sh"
#   tm_init DIR || skip...
#
# and anything else runs one function a call, with TM_SOCK and TM_DIR (which
# tm_init prints as shell assignments) in the environment:
#
#   sh tests/tmux.sh init DIR        ->  TM_SOCK=...  TM_DIR=...
#   TM_SOCK=... TM_DIR=... sh tests/tmux.sh wait tut -S 'some text' 30
#
# What it does:
# - a private server: tmux -L on a socket name of this run alone, no
#   configuration file (-f /dev/null);
# - a keep-alive session ("keep") for the server's whole life, so that
#   killing a case's session never leaves the server with none: its exit
#   would race the next case's new-session ("server exited unexpectedly",
#   once seen under load);
# - a case's program runs inside a small script that records `stty -a`
#   before and after it, its pid and its exit status (in TM_DIR), then
#   prints TM-PANE-ENDED and stays, so the screen it left can be read;
# - every wait polls the screen every 0.1 s with a limit (counted in
#   polls, so a loaded machine only waits longer).
#
#   tm_init DIR              start the server; records go in DIR/tmux/
#   tm_end                   kill the server (t_atexit runs it)
#   tm_run S W H DIR [-e VAR=VALUE]... CMD...
#                            a fresh session S, W x H, running CMD in DIR
#                            (inside the recording script)
#   tm_new S W H [-e VAR=VALUE]... CMD...   a fresh session S running CMD as is
#   tm_kill S                end session S
#   tm_pane S                print the screen (capture-pane -p)
#   tm_keys S KEY...         send-keys (tmux key names, or text)
#   tm_type S TEXT           send TEXT literally (send-keys -l)
#   tm_wait S MODE TEXT [SECONDS]   until the screen has TEXT (10 s unless
#                            SECONDS): MODE -F a fixed string in a row, -E an
#                            extended regex, -S a fixed string with runs of
#                            blanks counted as one space on both sides, -J a
#                            fixed string in the rows joined without newlines
#   tm_gone S TEXT [SECONDS] until the screen no longer has TEXT (5 s)
#   tm_resize S W H          resize-window, then wait until the pane is W x H
#   tm_ended S [SECONDS]     wait until the program in S ended (10 s); then
#                            TM_STATUS is its status ("exit=N")
#   tm_stty_same             `stty -a` after the program is what it was before
#   tm_pid                   the pid of the program in the last tm_run
#   tm_cmd ARGS...           any other tmux command on this server

tm_cmd() { tmux -L "$TM_SOCK" -f /dev/null "$@"; }

tm_init() {
  TM_DIR=$1/tmux
  mkdir -p "$TM_DIR" || return 1
  TM_SOCK=s42test-$$-$(od -An -N4 -tx4 /dev/urandom | tr -d ' ')
  export TM_SOCK TM_DIR
  cat > "$TM_DIR/pane.sh" <<'EOF'
# the pane's program: CMD between two `stty -a`, then its status
rec=$1
cd "$2" || exit 1
shift 2
trap : INT      # Ctrl-C is for the program (s42 tui exits 130), not for this script
stty -a > "$rec/stty.before"
sh -c 'echo $$ > "$0/pid"; exec "$@"' "$rec" "$@"
echo "exit=$?" > "$rec/status"
stty -a > "$rec/stty.after"
echo TM-PANE-ENDED
exec sleep 600
EOF
  if command -v t_atexit >/dev/null 2>&1; then t_atexit tm_end; fi
  tm_cmd new-session -d -s keep -x 20 -y 5 'sleep 86400'
}

tm_end() {   # the server, and its socket file (which tmux leaves behind)
  tm_cmd kill-server 2>/dev/null
  rm -f "${TMUX_TMPDIR:-/tmp}/tmux-$(id -u)/$TM_SOCK"
  return 0
}

tm_kill() { tm_cmd kill-session -t "$1" 2>/dev/null; return 0; }

tm_new() {
  tm_s_=$1 tm_w_=$2 tm_h_=$3
  shift 3
  tm_kill "$tm_s_"
  tm_cmd new-session -d -s "$tm_s_" -x "$tm_w_" -y "$tm_h_" "$@"
}

tm_run() {
  tm_s_=$1 tm_w_=$2 tm_h_=$3
  tm_d_=$(cd "$4" && pwd) || return 1
  shift 4
  tm_kill "$tm_s_"
  rm -f "$TM_DIR/status" "$TM_DIR/pid" "$TM_DIR/stty.before" "$TM_DIR/stty.after"
  # -e VAR=VALUE... CMD...  ->  -e VAR=VALUE... sh pane.sh REC DIR CMD...
  # (no arrays in sh: the -e pairs go to the end, the script after them,
  # then the command's words are rotated round behind it)
  tm_k_=$#
  while [ $# -gt 0 ] && [ "$1" = -e ]; do
    set -- "$@" "$1" "$2"
    shift 2
    tm_k_=$((tm_k_ - 2))
  done
  set -- "$@" sh "$TM_DIR/pane.sh" "$TM_DIR" "$tm_d_"
  while [ "$tm_k_" -gt 0 ]; do
    set -- "$@" "$1"
    shift
    tm_k_=$((tm_k_ - 1))
  done
  tm_cmd new-session -d -s "$tm_s_" -x "$tm_w_" -y "$tm_h_" "$@"
}

tm_pane() { tm_cmd capture-pane -p -t "$1" 2>/dev/null; }

tm_keys() {
  tm_s_=$1
  shift
  tm_cmd send-keys -t "$tm_s_" "$@"
}

tm_type() { tm_cmd send-keys -t "$1" -l "$2"; }

# tm_has_ S MODE TEXT: the screen has it now
tm_has_() {
  case $2 in
    -S) tm_pane "$1" | tr -s '[:blank:]' ' ' | grep -qF -- "$(printf '%s' "$3" | tr -s '[:blank:]' ' ')" ;;
    -J) tm_pane "$1" | tr -d '\n' | grep -qF -- "$3" ;;
    *) tm_pane "$1" | grep -q "$2" -- "$3" ;;
  esac
}

tm_poll_() {   # tm_poll_ SECONDS CMD...: CMD every 0.1 s until it succeeds
  tm_lim_=$(($1 * 10))
  shift
  tm_n_=0
  while [ "$tm_n_" -lt "$tm_lim_" ]; do
    "$@" && return 0
    sleep 0.1
    tm_n_=$((tm_n_ + 1))
  done
  "$@"
}

tm_wait() { tm_poll_ "${4:-10}" tm_has_ "$1" "$2" "$3"; }

tm_hasnt_() { ! tm_pane "$1" | grep -qF -- "$2"; }
tm_gone() { tm_poll_ "${3:-5}" tm_hasnt_ "$1" "$2"; }

tm_size_is_() { [ "$(tm_cmd display -p -t "$1" '#{pane_width}x#{pane_height}')" = "$2x$3" ]; }
tm_resize() {
  tm_cmd resize-window -t "$1" -x "$2" -y "$3" && tm_poll_ 10 tm_size_is_ "$1" "$2" "$3"
}

tm_ended_() { [ -f "$TM_DIR/status" ] && tm_has_ "$1" -F TM-PANE-ENDED; }
tm_ended() {
  TM_STATUS=
  tm_poll_ "${2:-10}" tm_ended_ "$1" || return 1
  TM_STATUS=$(cat "$TM_DIR/status")
}

tm_stty_same() { cmp -s "$TM_DIR/stty.before" "$TM_DIR/stty.after"; }

tm_pid() { cat "$TM_DIR/pid" 2>/dev/null; }

# run as a command: one function a call (tutorial.py)
case ${0##*/} in
  tmux.sh)
    tm_f_=$1
    shift
    case $tm_f_ in
      init)
        tm_init "$@" || exit 1
        echo "TM_SOCK=$TM_SOCK"
        echo "TM_DIR=$TM_DIR" ;;
      end|run|new|kill|pane|keys|type|wait|gone|resize|stty_same|pid|cmd)
        "tm_$tm_f_" "$@" ;;
      ended)
        tm_ended "$@" || exit 1
        echo "$TM_STATUS" ;;
      *)
        echo "tests/tmux.sh: no function $tm_f_" >&2
        exit 2 ;;
    esac ;;
esac
