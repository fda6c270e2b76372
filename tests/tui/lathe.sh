#!/bin/sh
# End-to-end tests of `s42 tui FILE.u22`: the 2У22 panel (the 16Б16Ф3
# lathe on the neutral runner) in a real 80x24 terminal, through the
# terminal tests' driver tests/tmux.sh: the DG and DI pages, Пуск to the
# end and a new cycle, single block (П/АВТ), block skip (U/), optional stop
# (ST), Стоп as a hold, reset, a run-time error on the message line, and the
# editor's check of a broken block.
#   sh tests/tui/lathe.sh ./s42
S42=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
. "$HERE/../lib.sh"
. "$HERE/../tmux.sh"
if ! t_have tmux; then
  echo "tui lathe: tmux is not installed: the terminal tests were skipped (sh scripts/deps.sh installs it)"
  exit 0
fi
export LC_ALL=C.UTF-8
t_init "tui lathe"
WORK=$T/work
mkdir -p "$WORK"
tm_init "$T" || { bad "tmux did not start"; t_done; }
TW=80 TH=24

start() {
  t_case "$1"
  shift
  tm_run s42 "$TW" "$TH" "$WORK" -e LC_ALL=C.UTF-8 -e TERM=screen "$S42" tui "$@"
}
pane() { tm_pane s42; }
keys() { tm_keys s42 "$@"; }
t_on_bad() { pane | sed 's/^/    | /'; }
wait_for() { tm_wait s42 "$1" "$2" "${3:-10}"; }
see() { if wait_for -F "$1" "$2"; then ok; else bad "'$1' did not appear"; fi; }
see_re() { if wait_for -E "$1" "$2"; then ok; else bad "/$1/ did not appear"; fi; }
gone() { if tm_gone s42 "$1" 5; then ok; else bad "'$1' stayed"; fi; }
ended() {
  if tm_ended s42 10; then
    if [ "$TM_STATUS" = "exit=$1" ]; then ok; else bad "quit with $TM_STATUS, expected exit=$1"; fi
    if tm_stty_same; then ok; else bad "the terminal settings changed"; fi
  else
    bad "s42 tui did not quit"
  fi
}
modeline() { pane | sed -n "$((TH - 2))p"; }
msgline() { pane | sed -n "$((TH - 1))p"; }
# no row wider than the terminal; a row that ends in a frame is exactly as wide
layout() {
  pane | python3 -c '
import sys
w = int(sys.argv[1])
rows = sys.stdin.read().split("\n")
bad = ["row %d is %d columns: %r" % (i, len(r), r) for i, r in enumerate(rows[1:-4], 2)
       if len(r) > w or (r and r[-1] in "│┐┘─" and len(r) != w)]
print("\n".join(bad[:5]))
sys.exit(1 if bad else 0)' "$1" > "$TM_DIR/layout.out" 2>&1
  if [ $? -eq 0 ]; then ok; else bad "layout $1: $(cat "$TM_DIR/layout.out")"; fi
}

cp /work/shared/spec/dialects/examples/2u22/fig1_9.u22 "$WORK/fig1_9.u22" 2>/dev/null ||
  cp "$ROOT/programs/2u22/fig1_9.u22" "$WORK/fig1_9.u22"

# ---- 1. Fig. 1.9: the DG page, Пуск to the end, a new cycle ----
start fig19 fig1_9.u22
see "ready: Пуск starts the cycle"
see "┌─ fig1_9.u22 ─"
see " DG ─ DI "
see_re "│X +\+0\.000 +│$"                         # DG: X (a diameter) and Z at power-on
see_re "│Z +\+0\.000 +│$"
see "part zero"
see_re "^ АВТ  "                                  # the mode line: automatic
see "g Пуск s Стоп b П/АВТ u U/ t ST r reset p page"
layout 80
keys f                                          # as fast as possible
see "speed: as fast as possible"
keys g
see "the program ended: 19 blocks" 20
see_re "│X +\+100\.000 +│$"                       # the end of Fig. 1.9: Ø100, Z 200
see_re "│Z +\+200\.000 +│$"
see_re "│MX +\+100\.000"
see_re "│ >20 N19 M02"                            # the last block is marked
see_re "^ АВТ +end  \|  N19 line 20"
see "warning: F10 mm/rev"                       # N14, N17, N18: the feed is cut, with a warning
keys g                                          # Пуск after the end: a new cycle from the start
see_re "^ АВТ +end  \|  N19 line 20  \|  cycle 2 " 20   # the slides stayed: the time goes on
see "the program ended: 19 blocks"
keys F1
see "s42 tui: the 2У22 panel"
see "U/: block skip"
keys Escape
gone "s42 tui: the 2У22 panel"
keys q
ended 0

# ---- 2. single block: each block waits; Пуск runs one; DI shows G95 after N13 ----
start single fig1_9.u22
see "ready: Пуск starts the cycle"
keys f b
see_re "^ П/АВТ  "
keys g                                          # N1 runs, N2 waits before it starts
see "N2 waits: single block (П/АВТ): Пуск (F5 or g) starts it"
see_re "│ > 3 N2 F1000 X4100"
see_re "│X +\+0\.000 +│$"
keys g
see "N3 waits: single block"
see_re "│ > 4 N3 F100 X0"
see_re "│X +\+41\.000 +│$"                        # N2 went to Ø41
keys g
see "N4 waits: single block"
see_re "│X +\+0\.000 +│$"                         # N3: facing to Ø0
n=4
while [ $n -lt 13 ]; do keys g; n=$((n + 1)); see "N$n waits: single block"; done
keys p                                          # the DI page
see "DI  П/АВТ  waits: Пуск"
see "N00013"
see "G G01 G90 G23 G94 G97"                     # before N13: G94
keys g
see "N14 waits: single block"
see "N00014"
see "G G01 G90 G23 G95 G97"                     # N13 switched to G95 ...
see_re "│T02 "                                   # ... and to tool 2
keys p
see "DG  position"
keys s                                          # Стоп in a wait ends the cycle
see "Стоп: the cycle was stopped at N14"
see_re "^ П/АВТ +stopped"
keys b
see "АВТ: automatic, the blocks run on"
keys g
see_re "^ АВТ +end  \|  N19 line 20  \|  cycle 2 " 20
see "the program ended: 19 blocks"
keys q
ended 0

# ---- 3. machine speed: Стоп holds the clock, Пуск goes on; reset ----
start hold fig1_9.u22
see "ready: Пуск starts the cycle"
keys g
see_re "running  \|  N3 line 4" 10               # N3: 41 mm at F100, some 12 s
keys s
see "feed hold (Стоп)"
c1=$(modeline | grep -o '[0-9.]* s ')
sleep 0.6
c2=$(modeline | grep -o '[0-9.]* s ')
if [ -n "$c1" ] && [ "$c1" = "$c2" ]; then ok; else bad "the clock runs in a hold ('$c1', '$c2')"; fi
keys g
see "Пуск: the cycle goes on"
sleep 0.6
c3=$(modeline | grep -o '[0-9.]* s ')
if [ -n "$c3" ] && [ "$c3" != "$c2" ]; then ok; else bad "the clock does not go on after Пуск ('$c2', '$c3')"; fi
keys Tab i                                      # no editing while a cycle is on
see "the cycle is running: stop it"
keys Tab r                                      # reset
see "reset: the cycle is abandoned"
see "ready: Пуск starts the cycle"
keys q
ended 0

# ---- 4. block skip (U/) and optional stop (ST) ----
printf '%%\nN1 G01 G90 G94 F1000 X1000 Z0\n/N2 X2000\nN3 Z-1000 M01\nN4 M02\n' > "$WORK/skip.u22"
start skip skip.u22
see "ready: Пуск starts the cycle"
keys f g                                        # U/ off: /N2 runs; ST off: M01 does not stop
see "the program ended: 4 blocks" 10
see_re "│X +\+20\.000 +│$"
keys u
see "U/: block skip on"
see_re "^ АВТ U/  "
keys g
see "the program ended: 3 blocks" 10            # /N2 is passed over
see_re "│X +\+10\.000 +│$"
see_re "│Z +-10\.000 +│$"
keys t
see "ST: optional stop on"
see_re "^ АВТ ST U/  "
keys g
see "N3 waits: a programmed stop: Пуск (F5 or g) goes on"
see_re "│ > 4 N3 Z-1000 M01"
keys g
see "the program ended: 3 blocks" 10
keys u t
see "ST off: M01 does not stop"
see_re "^ АВТ  "
keys q
ended 0

# ---- 5. a run-time error: on the message line, with its block and code ----
printf '%%\nN1 G01 G90 G94 F1000 X1000 Z0\nN2 Z-70000\nN3 M02\n' > "$WORK/travel.u22"
start error travel.u22
see "ready: Пуск starts the cycle"
keys f g
see "3:1 error N2 [E-TRAVEL]: Z -700.00 mm is outside the travel"
see_re "error N2 E-TRAVEL  \|  N2 line 3"
see_re "│ > 3 N2 Z-70000"
see_re "│X +\+10\.000 +│$"                        # N1 stays done, N2 did not move
keys q
ended 0

# ---- 6. the editor: a broken block is an error at its line; Пуск refuses it ----
start editor fig1_9.u22
see "ready: Пуск starts the cycle"
keys Tab
see "edit: fig1_9.u22"
keys Home i
see "insert after line 1:"
tm_type s42 "N5 G77"
keys Enter
see "line 2 inserted"
see_re "│!\* 2 N5 G77"                           # marked as an error at once
see "1 error: F8 lists it"
keys c
see "check: 1 error, 0 warnings"
see "2:4 error N5: G77 is no 2У22 function"
see "[E-FUNC]"
keys Tab g                                      # Пуск with an error: no cycle
see "the program has 1 error: the cycle does not start"
keys Tab d                                      # delete it: back to the file's text
see "line 2 deleted"
keys c
see "check: 0 errors, 0 warnings"
keys Tab f g
see "the program ended: 19 blocks" 20
keys q
ended 0

t_done
