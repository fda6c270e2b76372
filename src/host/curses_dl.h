/* ncursesw, loaded with dlopen when `s42 tui` starts (main.c): linked
 * directly, every `s42 run` mapped it and libtinfo for the terminal alone.
 * tui.c includes this after <curses.h> and uses the functions and the
 * variables (stdscr, LINES, COLS) by their usual names, the macros of
 * curses.h included; one it uses and this table lacks does not link.
 * Without curses.h before it (main.c) it declares s42_curses_load alone. */
#ifndef S42_CURSES_DL_H
#define S42_CURSES_DL_H

#include <stddef.h>

/* Load ncursesw (and libtinfo, its dependency) and resolve everything in
 * the table below (once; then it stays): 0, or -1 with a message naming
 * the library in err. */
int s42_curses_load(char *err, size_t n);

#ifdef NCURSES_VERSION

#if NCURSES_REENTRANT
#error "curses_dl.h: stdscr, LINES and COLS are functions in a reentrant ncurses: add them to the table so"
#endif

#define S42_CURSES_STR_(x) #x
#define S42_CURSES_STR(x) S42_CURSES_STR_(x)
/* the library of the headers compiled against: libncursesw.so.6 */
#define S42_CURSES_SONAME "libncursesw.so." S42_CURSES_STR(NCURSES_VERSION_MAJOR)

/* functions and variables alike: the table holds their addresses */
#define S42_CURSES_SYMS(F) \
  F(COLS) \
  F(LINES) \
  F(stdscr) \
  F(cbreak) \
  F(curs_set) \
  F(delscreen) \
  F(endwin) \
  F(has_colors) \
  F(init_pair) \
  F(intrflush) \
  F(keypad) \
  F(newterm) \
  F(nodelay) \
  F(noecho) \
  F(nonl) \
  F(set_escdelay) \
  F(setcchar) \
  F(start_color) \
  F(tigetstr) \
  F(use_default_colors) \
  F(wadd_wch) \
  F(waddch) \
  F(werase) \
  F(wget_wch) \
  F(wmove) \
  F(wrefresh)

struct s42_curses {
#define S42_CURSES_PTR(name) __typeof__(name) *name;
  S42_CURSES_SYMS(S42_CURSES_PTR)
#undef S42_CURSES_PTR
};
extern struct s42_curses s42_curses;

#ifndef S42_CURSES_DL_IMPL
#define COLS (*s42_curses.COLS)
#define LINES (*s42_curses.LINES)
#define stdscr (*s42_curses.stdscr)
#define cbreak (*s42_curses.cbreak)
#define curs_set (*s42_curses.curs_set)
#define delscreen (*s42_curses.delscreen)
#define endwin (*s42_curses.endwin)
#define has_colors (*s42_curses.has_colors)
#define init_pair (*s42_curses.init_pair)
#define intrflush (*s42_curses.intrflush)
#define keypad (*s42_curses.keypad)
#define newterm (*s42_curses.newterm)
#define nodelay (*s42_curses.nodelay)
#define noecho (*s42_curses.noecho)
#define nonl (*s42_curses.nonl)
#define set_escdelay (*s42_curses.set_escdelay)
#define setcchar (*s42_curses.setcchar)
#define start_color (*s42_curses.start_color)
#define tigetstr (*s42_curses.tigetstr)
#define use_default_colors (*s42_curses.use_default_colors)
#define wadd_wch (*s42_curses.wadd_wch)
#define waddch (*s42_curses.waddch)
#define werase (*s42_curses.werase)
#define wget_wch (*s42_curses.wget_wch)
#define wmove (*s42_curses.wmove)
#define wrefresh (*s42_curses.wrefresh)
#endif

#endif /* NCURSES_VERSION */

#endif
