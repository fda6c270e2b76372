#!/bin/sh
# End-to-end tests of `s42 tui` in a real terminal: tmux runs it in a
# detached pane on a private socket (100x30, or TW x TH: 80x24 and 120x40
# too), send-keys types, capture-pane reads the screen, all through the
# terminal tests' driver tests/tmux.sh.  Every wait polls the pane until the
# text appears, with a limit, so a slow machine only makes the tests slower.
# The pane runs the terminal inside the driver's small shell script that
# records `stty -a` before and after and the exit status, so the restored
# terminal is checked too.
#   sh tests/tui/run.sh ./s42
S42=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
. "$HERE/../lib.sh"
. "$HERE/../tmux.sh"
if ! t_have tmux; then
  echo "tui: tmux is not installed: the terminal tests were skipped (sh scripts/deps.sh installs it)"
  exit 0
fi
export LC_ALL=C.UTF-8                      # the tmux client prints the pane as UTF-8
# (under make asan the panes inherit ASAN_OPTIONS through the tmux server:
# a leak or an error shows as a wrong exit status below)
t_init tui
WORK=$T/work
mkdir -p "$WORK"
# the driver (tests/tmux.sh): a private server with a session that lives as
# long as the test, each case's terminal in the recording script
tm_init "$T" || { bad "tmux did not start"; t_done; }

# start NAME LOCALE ARGS...: a fresh pane running s42 tui ARGS in WORK,
# TW x TH (100x30 unless they are set)
start() {
  t_case "$1"
  loc=$2
  shift 2
  tm_run s42 "${TW:-100}" "${TH:-30}" "$WORK" -e LC_ALL="$loc" -e TERM=screen "$S42" tui "$@"
}
pane() { tm_pane s42; }
keys() { tm_keys s42 "$@"; }
# a failure shows the screen
t_on_bad() { pane | sed 's/^/    | /'; }
# wait_for MODE TEXT [SECONDS]: poll until the pane has (MODE -F or -E) TEXT
wait_for() { tm_wait s42 "$1" "$2" "${3:-10}"; }
see() { if wait_for -F "$1" "$2"; then ok; else bad "'$1' did not appear"; fi; }
see_re() { if wait_for -E "$1" "$2"; then ok; else bad "/$1/ did not appear"; fi; }
gone() {   # the text leaves the pane
  if tm_gone s42 "$1" 5; then ok; else bad "'$1' stayed"; fi
}
# ended STATUS: the terminal quit with that status and left the tty as it was
ended() {
  if tm_ended s42 10; then
    if [ "$TM_STATUS" = "exit=$1" ]; then ok; else bad "quit with $TM_STATUS, expected exit=$1"; fi
    if tm_stty_same; then ok; else
      bad "the terminal settings changed:"
      diff "$TM_DIR/stty.before" "$TM_DIR/stty.after" | sed 's/^/    /'
    fi
  else
    bad "s42 tui did not quit"
  fi
}
# msgline: the message line (the last row but one of the pane)
msgline() { pane | sed -n "$((${TH:-30} - 1))p"; }
# layout: no row is wider than W, every row that ends in a frame is exactly
# W columns (capture-pane drops trailing blanks), pure ASCII when asked
layout() {
  pane | python3 -c '
import sys
w, ascii_only = int(sys.argv[1]), sys.argv[2] == "ascii"
rows = sys.stdin.read().split("\n")
bad = []
for i, r in enumerate(rows[1:-3], 2):
    if len(r) > w or (r and r[-1] in "│┐┘|+─-" and len(r) != w):
        bad.append("row %d is %d columns: %r" % (i, len(r), r))
    if ascii_only and any(ord(c) > 126 for c in r):
        bad.append("row %d is not ASCII: %r" % (i, r))
print("\n".join(bad[:5]))
sys.exit(1 if bad else 0)' "$1" "$2" > "$TM_DIR/layout.out" 2>&1
  if [ $? -eq 0 ]; then ok; else bad "layout $1 $2: $(cat "$TM_DIR/layout.out")"; fi
}

cp "$ROOT/programs/drill_dialog.kp" "$WORK/drill.kp"

# ---- 1. the drill dialog: answers, a refused one, a correction with ЗБ ----
start dialog C.UTF-8 drill.kp
see "ready: Пуск starts the cycle"
see "┌─ 2С42-65 ─"
layout 100 utf8
keys g
see "ДІАМЕТР, МКМ............."
keys 3 5 0 0 0 Enter
see "ДІАМЕТР, МКМ.............  35000"
see "ДОВЖИНА, МКМ"
keys 9 5 0 0 0 Enter
see "КУТ ЗАГОСТРЕННЯ, ГРАД...."
keys 1 4 0 Enter                             # above 130: refused
see "знач. більше допустимого"
see_re "^│ >42 №07 G28 /90:130/ R40"         # the waiting block is highlighted
keys 1 1 9 BSpace                           # ЗБ takes the 9 back
see "КУТ ЗАГОСТРЕННЯ, ГРАД....11_"
keys 8 Enter
see "КУТ ЗАГОСТРЕННЯ, ГРАД....    118"
keys 3 3 3 5 0 0 Enter
see "Введення завершено"
see "          КІНЕЦЬ ВВОДУ"
see_re "R40 +118  N7"
see_re "R3 +333500  N9"
see_re "R0 +35000  N3"
keys g                                       # Пуск: the cycle, at machine speed
see "|  running  |" 2
see_re "wheel cw"
see_re "│X +-?[0-9]+\.[0-9]{3} mm" 1
sleep 1
x1=$(pane | grep -o '│X  *[-0-9.]* mm' | head -1)
sleep 1
x2=$(pane | grep -o '│X  *[-0-9.]* mm' | head -1)
if [ -n "$x1" ] && [ "$x1" != "$x2" ]; then ok; else bad "X does not move at machine speed ('$x1', '$x2')"; fi
keys s                                       # Стоп: feed hold
see "feed hold (Стоп)"
h1=$(pane | grep -o 'time  *[0-9.]* s' | head -1)
sleep 0.5
h2=$(pane | grep -o 'time  *[0-9.]* s' | head -1)
if [ "$h1" = "$h2" ]; then ok; else bad "the clock runs in a feed hold ('$h1', '$h2')"; fi
keys g
see "|  running  |"
keys f                                       # as fast as possible, to the end
see "end (M2)" 20
see "КУТ НАХИЛУ КАНАВКИ    18248"
see_re "│A +1080\.000 deg"
see_re "│X +-5\.000 mm"
see "the program ended (M2): 51 blocks"
keys q
ended 0

# ---- 2. the editor: Рус, insert, check, delete, replace, undo, save ----
start editor C.UTF-8 drill.kp
see "ready: Пуск starts the cycle"
keys Tab
see "edit: drill.kp"
keys Home
i=0
while [ $i -lt 35 ]; do keys Down; i=$((i + 1)); done
see "*36 №01 G33 /СВЕРДЛО/ ^"
keys i
see "insert after line 36:"
keys "G33 /"
keys C-r                                     # Рус
see "│АВТОМАТ R"
see "|  Рус"
keys "ZATO%KA"                               # table 3.4: З А Т О Ч К А
keys F4                                      # Рус off
gone "│АВТОМАТ R"
keys "/ ^" Enter
see "*37 G33 /ЗАТОЧКА/ ^"
see "drill.kp [modified]"
keys c
see "check: 0 errors, 0 warnings"
keys i "G99 ^" Enter c
see "[E-FUNC]"
see "!*38 G99 ^"
see "check: 1 error, 0 warnings"
keys d c
see "check: 0 errors, 0 warnings"
keys Up Enter
see "line 37: G33 /ЗАТОЧКА/ ^"
keys C-u "G33 /DRILL/ ^" Enter
see "*37 G33 /DRILL/ ^"
keys w
see "saved drill.kp (62 lines)"
if sed -n 36,37p "$WORK/drill.kp" | tr '\n' '|' | grep -qF '№01 G33 /СВЕРДЛО/ ^|G33 /DRILL/ ^|'; then ok; else
  bad "the saved file: $(sed -n 35,38p "$WORK/drill.kp")"
fi
if ls "$WORK" | grep -q tmp; then bad "a temporary file was left: $(ls "$WORK")"; else ok; fi
if "$S42" check "$WORK/drill.kp" 2>/dev/null; then ok; else bad "the saved program does not check"; fi
keys u
see "*37 G33 /ЗАТОЧКА/ ^"
keys q
see "unsaved changes: quit anyway? (y/n)"
keys n
see "cancelled"
keys q y
ended 0
if grep -qF "G33 /DRILL/ ^" "$WORK/drill.kp" && ! grep -qF "ЗАТОЧКА" "$WORK/drill.kp"; then ok; else
  bad "the file changed without a save"
fi

# ---- 3. resize: the layout follows the window; Ctrl-C restores the tty ----
cp "$ROOT/programs/drill_dialog.kp" "$WORK/drill.kp"
start resize C.UTF-8 drill.kp
see "┌─ machine ─"
tm_resize s42 70 24
gone "┌─ drill.kp ─"                             # narrow: the machine stays, the listing goes
see "┌─ machine ─"
see "┌─ 2С42-65 ─"
layout 70 utf8
tm_resize s42 30 15
see "the terminal is 30x15: s42 tui"            # wrapped at words in 30 columns
see "needs at least 34x21; q quits"
tm_resize s42 120 40
see "┌─ machine ─"
layout 120 utf8
# back to the size it started with before quitting, so that the tty's own
# settings compare equal: wait until the pane and the layout are 100x30
# (tmux applies a resize in its own time; under load it lags)
tm_resize s42 100 30
see "┌─ machine ─"
wide100() { pane | grep -q '^┌.\{99\}$'; }
t_wait 10 wide100
layout 100 utf8
keys C-c
ended 130

# ---- 4. a terminal that is not UTF-8: one ASCII character per cell ----
start ascii C drill.kp
see "+- 2S42-65 -"
see "; SVERDLO, DIALOG: zatocuv"
layout 100 ascii
keys g 3 5 0 0 0 Enter                       # typed ahead: the dialog is there at once
see "DIAMETR, MKM.............  35000"
keys F4
see "|AVTOMAT R"
layout 100 ascii
kill -TERM "$(tm_pid)"
ended 143

# ---- 5. manual mode: G20 with a directive, jogs, ПС, Пуск ----
printf '№1 G20 M18 /ВІДВЕСТИ X/ ^\n№2 G01 X-2000 F600 ^\n№3 M02 ^\n' > "$WORK/g20.kp"
start manual C.UTF-8 g20.kp
keys g
see "│РУЧНИЙ"
see "ВІДВЕСТИ X"
see "N1 waits: ПС (Enter), then Пуск"
keys X X x j X                               # +1000 +1000 -1000, step 10000, +10000
see_re "│X +11\.000 mm"
keys g                                       # Пуск before ПС does not fit
see "Пуск does not fit here"
keys Enter g
see "end (M2)" 10
see_re "│X +9\.000 mm"
keys q
ended 0

# ---- 6. cycle exit in time, the feed override, M15 and --restart ----
printf '№1 R1+R1+1 ^\n№2 M15 G04 X+2 ^\n№3 PP5 ^\n№4 P1 ^\n№5 M02 ^\n' > "$WORK/loop.kp"
start loop C.UTF-8 loop.kp
keys g
see "M15 restart point saved in loop.kp.state"
see_re "R1 +[2-9] +N1"                       # going round
keys "<" "<"
see "F%         80 %"
keys e                                       # Вихід з циклу: the next PP5 is taken
see "end (M2)" 5
keys q
ended 0
start restart C.UTF-8 loop.kp --restart
keys g
see "restart: the cycle goes on at"
see_re "R1 +[0-9]+ +N1"
keys F7
see "end (M2)" 5
keys q
ended 0
printf '\n' >> "$WORK/loop.kp"                # the text changed: no restart
start refused C.UTF-8 loop.kp --restart
keys g
see "помилка в КП №1: повторний пуск"
see "[E-STATE]"
keys q
ended 0
cp "$WORK/loop.kp" "$WORK/loop.copy"          # --state naming the program: never replaced
start notstate C.UTF-8 loop.kp --state loop.kp
keys g
see "помилка в КП №2: повторний пуск"
see "loop.kp is not an s42 restart state"
cmp -s "$WORK/loop.kp" "$WORK/loop.copy" && ok || bad "the program was replaced by a state"
keys q
ended 0
mkfifo "$WORK/fifo.kp"                        # a FIFO as the program: refused, not waited on
start fifo C.UTF-8 fifo.kp
see "s42 tui: fifo.kp: is a FIFO, not a regular file"
ended 4

# ---- 8. the tooth search: the section move by jogs, P5 paged by + and - ----
printf '№1 G10 D1+50000 M10 M12 F6000 ^\n№2 M02 ^\n' > "$WORK/search.kp"
start search C.UTF-8 search.kp --tool "$ROOT/tests/toothsearch/t012_straight_noisy.tool"
see "ready: Пуск starts the cycle"
keys f g                                     # as fast as possible; Пуск
see "упор в перетин 1"
see "│РУЧНИЙ"
keys g                                       # the probe is in the flute: Пуск
see "упорку в переріз 2" 20
see "to section 2"
if msgline | grep -qF "to section 2"; then ok; else bad "the message line does not say what the header says: $(msgline)"; fi
keys j X X X                                 # step 10000: the table +30 mm
see_re "│X +30\.000 mm"
keys g
see "відвести упорку" 20
see "│РЕЗУЛЬТАТИ"
see "КРОКИ, 0.001°             1-8/12"
keys +
see "КРОКИ, 0.001°            9-12/12"
see " 12   "
keys -
see "КРОКИ, 0.001°             1-8/12"
keys Enter                                   # ПС: the probe is out
gone "відвести упорку"
keys g
see "end (M2)" 10
keys q
ended 0
start notool C.UTF-8 search.kp                # no --tool: Пуск says so, nothing starts
see "ready: Пуск starts the cycle"
keys g
see "needs a tool model: give --tool FILE"
see "ready: Пуск starts the cycle"
keys q
ended 0

# ---- 9. Стоп twice mid-move: the axes stay where the feed hold stopped them ----
cp "$ROOT/programs/drill_point.kp" "$WORK/point.kp"
start stopmid C.UTF-8 point.kp
see "ready: Пуск starts the cycle"
keys g
see "|  running  |"
sleep 2.5                                    # well inside sub 40's first lip stroke
keys s
see "feed hold (Стоп)"
x1=$(pane | grep -o '│X  *[-0-9.]* mm' | head -1)
keys s
see "Стоп: the cycle was stopped"
x2=$(pane | grep -o '│X  *[-0-9.]* mm' | head -1)
if [ -n "$x1" ] && [ "$x1" = "$x2" ]; then ok; else bad "X moved when the held cycle stopped ('$x1', '$x2')"; fi
see_re "│feed +0\.0 mm/min"
keys q
ended 0

# ---- 10. the override within a move, 0 % and Стоп hold it (feed 0); single block; a breakpoint ----
printf '%s\n' '; a 60 s stroke, then three short ones' '№1 G01 X+60000 F60 ^' '№2 G01 X-1000 F600 ^' \
  '№3 G01 X-1000 ^' '№4 G01 X-1000 ^' '№5 M02 ^' > "$WORK/long.kp"
TW=80 TH=24 start override C.UTF-8 long.kp
see "ready: Пуск starts the cycle"
keys g
see_re "│feed +60\.0 mm/min"
keys '>' '>' '>' '>' '>'                      # 150 % while N1's 60 s stroke runs: at once
see_re "│feed +90\.0 mm/min"
see_re "F% +150 %"
keys s                                       # feed hold: the feed reads 0
see_re "│feed +0\.0 mm/min"
keys g
see_re "│feed +90\.0 mm/min"
for i in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15; do keys '<'; done
see "feed override 0 %: the move stands"
see_re "│feed +0\.0 mm/min"
x1=$(pane | grep -o '│X  *[-0-9.]* mm' | head -1)
sleep 0.5
x2=$(pane | grep -o '│X  *[-0-9.]* mm' | head -1)
if [ -n "$x1" ] && [ "$x1" = "$x2" ]; then ok; else bad "X moved at 0 % ('$x1', '$x2')"; fi
keys g
see "the feed override is at 0 %: raise it (>)"
keys b                                       # single block from the next block on
see "single block (П): each block waits for Пуск"
see "|  single block"
keys f                                       # fast: N1 ends at once (at 0 % it still stands)
keys '>' '>' '>' '>' '>' '>' '>' '>' '>' '>'
see "N2 waits: single block: Пуск (F5 or g) starts it"
keys g
see "N3 waits: single block"
keys b B 5 Enter                             # automatic again, a breakpoint at N5
see "breakpoint at N5: it waits for Пуск before it starts"
keys g
see "N5 waits: breakpoint: Пуск (F5 or g) starts it"
keys g
see "the program ended (M2): 5 blocks"
keys q
ended 0

# ---- 7. no program, then open one; a missing file; not a terminal ----
start empty C.UTF-8
see "no program: F3 (or o) opens one"
keys o
see "open file:"
keys "drill.kp" Enter
see "drill.kp: 61 lines; 0 errors"
see "; СВЕРДЛО, ДІАЛОГ: заточув"
keys F10
ended 0
start missing C.UTF-8 nodir/nosuch.kp          # a new file's directory must be there
see "TM-PANE-ENDED"
ended 4
if pane | grep -qF "nodir/nosuch.kp: No such file"; then ok; else bad "no message for a missing file"; fi
t_case cli
"$S42" tui "$WORK/drill.kp" < /dev/null > "$WORK/out" 2>&1
st=$?
if [ $st -eq 2 ] && grep -q "must be a terminal" "$WORK/out"; then ok; else bad "not a terminal: status $st: $(cat "$WORK/out")"; fi
"$S42" tui "$WORK/drill.kp" --operator x.op > "$WORK/out" 2>&1
st=$?
if [ $st -eq 2 ] && grep -q "operator scripts are for s42 run" "$WORK/out"; then ok; else bad "--operator: status $st"; fi

# ---- 10. 80x24: the machine, the block, the time, the key line's hints ----
cp "$ROOT/programs/drill_dialog.kp" "$WORK/drill.kp"
TW=80 TH=24 start small C.UTF-8 drill.kp
see "┌─ machine ─"
see "┌─ 2С42-65 ─"
see "┌─ drill.kp ─"
see_re "F1 keys q quit *$"
see "0 errors, 0 warnings."                      # a message in the pane, wrapped at words
layout 80 utf8
keys F1                                      # the help is taller than 24 rows: it scrolls
see "keys (Down: more)"
keys Down Down Down Down Down Down Down Down Down Down
see "quit (while a cycle runs: q twice)"
see "/ search, n N next / previous match, : go to line"
keys Escape
gone "quit (while a cycle runs"
keys g 3 5 0 0 0 Enter
see_re "│R0 +35000 N3"
keys 9 5 0 0 0 Enter 1 1 8 Enter 3 3 3 5 0 0 Enter g
see "|  running  |"
see_re "│X +-?[0-9]+\.[0-9]{3} mm"
see_re "│A +-?[0-9]+\.[0-9]{3} deg"
see_re "│F +[0-9]+ mm/min"
see_re "│feed +[0-9.]+ mm/min"
see_re "│F% +100 %"
see_re "│N[0-9]+  line [0-9]+"
see_re "│time +[0-9.]+ s x1"
see "─ messages ─"
see "Пуск: the cycle starts"
if pane | grep -qF "F1 shows the keys"; then ok; else bad "the messages pane shows one message"; fi
layout 80 utf8
keys s s
see "Стоп: the cycle was stopped"
keys q
ended 0
# 120x40: all three panes, the wide forms
TW=120 TH=40 start big C.UTF-8 drill.kp
see "┌─ machine ─"
see "┌─ messages ─"
see_re "│block -"
see "│jog step 1000"
layout 120 utf8
keys q
ended 0
# the messages wrap at words (100x30: 32 columns): every word in the pane
# is a whole word of the message (one longer than the message line)
cp "$ROOT/programs/drill_dialog.kp" "$WORK/a-program-with-a-long-name.kp"
start wrap C.UTF-8 a-program-with-a-long-name.kp
see "┌─ messages ─"
pane | python3 -c '
import sys
msg = "a-program-with-a-long-name.kp: 61 lines, 0 errors, 0 warnings.  Пуск (F5 or g) starts the cycle; F1 shows the keys"
rows = sys.stdin.read().split("\n")
top = [i for i, r in enumerate(rows) if "┌─ messages" in r][0]
x = rows[top].index("┌─ messages")
words = []
for r in rows[top + 1:]:
    if r[x] == "└":
        break
    words += r[x + 1:x + 33].split()
ok = words and all(w in msg.split() for w in words) and " ".join(words) in " ".join(msg.split())
sys.exit(0 if ok else 1)' && ok || bad "a message is not wrapped at words"
keys q
ended 0
# a long path does not cut the state out of the title
deep="$WORK/a-directory-with-a-rather-long-name/and-one-more-to-make-the-path-long"
mkdir -p "$deep"
cp "$ROOT/programs/drill_dialog.kp" "$deep/drill.kp"
TW=80 TH=24 start longpath C.UTF-8 "$deep/drill.kp"
see_re "^ …[^ ]*/drill\.kp  [|]  ready: Пуск starts the cycle"
keys q
ended 0

# ---- 11. why Пуск cannot start; cycle exit; q in a running cycle ----
printf '№1 G99 ^\n№2 G98 ^\n№3 M02 ^\n' > "$WORK/bad.kp"
start header C.UTF-8 bad.kp
see "|  2 errors: F8 lists them  |"
keys q
ended 0
start noprog C.UTF-8
see "|  no program: F3 opens one  |"
keys q
ended 0
printf '№1 R1+R1+1 ^\n№2 M15 G04 X+2 ^\n№3 PP5 ^\n№4 P1 ^\n№5 M02 ^\n' > "$WORK/loop.kp"
rm -f "$WORK/loop.kp.state"
start exitpp C.UTF-8 loop.kp
keys g
see "|  running  |"
keys q
see "a cycle is running: q again to quit, any other key goes on"
keys x
see "the cycle goes on"
see "|  running  |"
keys e
see "cycle exit: N3 → N5" 5
see "end (M2)" 5
keys q
ended 0
start quitrun C.UTF-8 loop.kp
keys g
see "|  running  |"
keys q q
ended 0

# ---- 12. the parameters page: every one; set one in a wait, not in a block ----
printf '№1 T11+5 T11+7 D1+3000 ^\n№2 G34 ^\n№3 G04 X+30 ^\n№4 M02 ^\n' > "$WORK/arr.kp"
start params C.UTF-8 arr.kp
keys p
see "┌─ parameters (no cycle yet) ─"
see_re "│R0 +0 "
keys g                                       # the panel's keys work on the page
see "N2 waits: Пуск (F5 or g) continues"
see "┌─ parameters ─"
keys NPage NPage NPage NPage
see_re "│R113 +0 "
see_re "│D1 +3000 "
see_re "│TK +0 "
see_re "│UG +0 "
see "│array 1: ptr 2 len 2"
see_re "│ 0 +5 "
see_re "│ 1 +7 "
see_re "│>2 +0 "
keys NPage
see "│array 2: ptr 0 len 0"
keys Home Down Down Down =
see "set R3 = 0"
keys 4 2 . 5 Enter                           # typing replaces the 0 it showed
see "R3 = 42.5, set from the panel at N2"
see_re "│R3 +42\.5 +panel"
see_re "│R3 +42\.5 "
keys End =
see "read-only: the program sets it"
keys Home Down Down Down g                   # Пуск: block 3 dwells 3 s
see "|  running  |"
keys = 1 Enter
see "R3: not set: a block is running"
keys p
see "┌─ arr.kp ─"
keys q q
ended 0

# ---- 13. progress: the estimate (at least, then exact) and the part done ----
cp "$ROOT/docs/tutorial/cycle.kp" "$WORK/cycle.kp"
rm -f "$WORK/cycle.kp.state"
start estimate C.UTF-8 cycle.kp
keys g
see "ПРОХОДІВ................._"
see "│estimate ≥ 0.00 s"                         # waits for the number: at least
keys 3 Enter
see_re "│estimate +13\.88 s +0 %"                  # the headless run with 3 passes: 13.8792 s
keys g
see "|  running  |"
see_re "│estimate +13\.88 s +[1-9][0-9]? %" 10
keys f
see "end (M2)" 10
see_re "│estimate +13\.88 s 100 %"
keys q
ended 0
TW=80 TH=24 start estnarrow C.UTF-8 cycle.kp
keys g 3 Enter
see_re "│of +13\.88 s +0%"
keys s s q
ended 0

# ---- 14. --restart: the dialog area and the parameters it holds ----
rm -f "$WORK/cycle.kp.state"
(cd "$WORK" && "$S42" run cycle.kp --operator "$ROOT/docs/tutorial/cycle.operator" > /dev/null)
start restarted C.UTF-8 cycle.kp --restart
keys g
see "restart: the cycle goes on at"
see "│         ПЕРЕДНЯ ГРАНЬ          │"
see "│ПРОХОДІВ.................      3│"
see_re "│R1 +3  restart"
see_re "│R2 +2  restart"
see_re "│estimate +13\.88 s"
keys f
see "end (M2)" 10
keys q
ended 0

# ---- 15. the editor: a new file, a prompt's name, undo to the saved text, a change on disk ----
rm -f "$WORK/new.kp"
start newfile C.UTF-8 new.kp
see "new.kp: a new file (the first save creates it)"
see "|  empty: Tab, then i writes a block  |"
keys Tab i "№1 G04 X+1 ^" Enter i "№2 M02 ^" Enter w
see "saved new.kp (2 lines)"
if [ "$(cat "$WORK/new.kp")" = "$(printf '№1 G04 X+1 ^\n№2 M02 ^')" ]; then ok; else bad "new.kp: $(cat "$WORK/new.kp")"; fi
see "|  ready: Пуск starts the cycle  |"
keys q
ended 0
printf '№1 G04 X+1 ^\n№2 M02 ^\n' > "$WORK/new.kp"     # (the same text, for a terminal that cannot make one)
start undo C.UTF-8 new.kp
see "|  ready: Пуск starts the cycle  |"
keys Tab Down
see "* 2 №2 M02 ^"
keys d
see "new.kp [modified]"
keys u                                       # back to the saved text: not modified
gone "[modified]"
printf '; written by another editor\n' >> "$WORK/new.kp"
keys d w
see "new.kp changed on disk since it was read: overwrite it? (y/n)"
keys n
see "not saved"
if grep -qF "another editor" "$WORK/new.kp"; then ok; else bad "the other editor's change was overwritten"; fi
keys w y
see "saved new.kp (1 line)"
if [ "$(cat "$WORK/new.kp")" = "№2 M02 ^" ]; then ok; else bad "new.kp after y: $(cat "$WORK/new.kp")"; fi
touch -d '2001-01-01' "$WORK/new.kp"         # only the time changed: no question
keys I "№1 G04 X+1 ^" Enter w
see "saved new.kp (2 lines)"
keys o
see "open file: new.kp"
keys "drill.kp" Enter                        # typed over the name it offered
see "drill.kp: 61 lines; 0 errors"
keys W
see "save as: drill.kp"
keys "new.kp" Enter                          # another file that is there: asks
see "new.kp exists: replace it? (y/n)"
keys n
see "not saved"
keys q
ended 0

# ---- 16. the editor: search, go to a line, long lines scroll across ----
cp "$ROOT/programs/drill_dialog.kp" "$WORK/drill.kp"
start find C.UTF-8 drill.kp
see "|  ready: Пуск starts the cycle  |"
keys Tab / G28 Enter
see "G28: line 6"
keys n
see "G28: line 38"
keys N
see "G28: line 6"
keys N
see "G28: line 44 (the search went on from the bottom)"
keys : 6 0 Enter
see "*60 №20 G01 G09 X-R51-R59 F+R…"
keys / "№01" Enter
see "№01: line 36 (the search went on from the top)"
keys / zzz Enter
see "not found: zzz"
keys : 1 Enter
see "* 1 ; СВЕРДЛО, ДІАЛОГ: заточу…"          # cut at the pane: … says there is more
keys Right Right Right Right Right Right
see "з діалогу."                               # the end of line 1, past the pane's 26 columns
keys Home / "уставками" Enter                   # a match out of view is brought into it
see "уставками: line 1"
see "уставками з діал"
keys Left Left Left Left Left Left Left Left
see "* 1 ; СВЕРДЛО, ДІАЛОГ: заточу…"
keys q
ended 0

t_done
