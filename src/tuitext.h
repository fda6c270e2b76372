/* What the terminal edits and shows, without curses: the program text as
 * lines (insert, replace, delete, one level of undo, atomic save), the
 * 2С42-65 Cyrillic keyboard map (seed table 3.4), and a one-column ASCII
 * stand-in for every character, for terminals that are not UTF-8. */
#ifndef S42_TUITEXT_H
#define S42_TUITEXT_H

#include <stddef.h>
#include <stdint.h>

struct tui_text {
  char **line;           /* UTF-8, without the line end */
  size_t n, cap;
  int crlf;              /* the file's lines ended with \r\n */
  int cr;                /* ... with \r alone (old Mac OS) */
  int final_eol;         /* the last line ended with a line end */
  /* the text before the last change, for undo */
  char **old;
  size_t nold;
  int have_old;
};

void tui_text_init(struct tui_text *t);
void tui_text_free(struct tui_text *t);
/* Replace the whole text with these bytes.  0, or -1 with err (out of
 * memory, a NUL byte: not a program text). */
int tui_text_set(struct tui_text *t, const char *buf, size_t n, char *err, size_t errn);
/* Read a file into the text; on failure the text stays as it was. */
int tui_text_load(struct tui_text *t, const char *path, char *err, size_t errn);
/* The whole text as one malloc'd buffer (*n bytes, NUL-terminated), as it
 * would be saved.  NULL when out of memory. */
char *tui_text_join(const struct tui_text *t, size_t *n);
/* Edits: insert before line i (i == n appends), replace line i, delete
 * line i.  Each keeps the text before it for tui_text_undo.  0, or -1
 * (out of memory or a bad index: nothing changed). */
int tui_text_insert(struct tui_text *t, size_t i, const char *s);
int tui_text_replace(struct tui_text *t, size_t i, const char *s);
int tui_text_delete(struct tui_text *t, size_t i);
/* Back to the text before the last edit (0), or -1 when there is none. */
int tui_text_undo(struct tui_text *t);
/* Save atomically: a temporary file beside it, fsync, rename over the old
 * file, fsync of the directory -- the file on disk is always either the old
 * text or the new one.  Keeps the old file's permissions.  0, or -1 with
 * err. */
int tui_text_save(const struct tui_text *t, const char *path, char *err, size_t errn);

/* The Cyrillic mode of the 2С42-65 keyboard (table 3.4): the letter a key
 * gives, or the key itself when the table has nothing for it.  Latin
 * letters give capitals, as the machine had no others. */
uint32_t tui_cyr_key(uint32_t key);
/* One printable ASCII character standing for code point c: itself when
 * ASCII, a transliteration of Cyrillic, '+' '-' '|' for box drawing, '?'
 * otherwise.  Always one column, so no layout moves. */
char tui_ascii(uint32_t c);
/* Encode one code point as UTF-8; returns the byte count (1-4). */
int tui_utf8(uint32_t c, char out[4]);

#endif
