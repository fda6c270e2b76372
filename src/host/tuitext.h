/* What the terminal edits and shows, without curses: the program text as
 * lines (insert, replace, delete, one level of undo, search, atomic save),
 * what the file on disk was when it was read (to notice a change before a
 * save), the 2С42-65 Cyrillic keyboard map (seed table 3.4), a one-column
 * ASCII stand-in for every character, for terminals that are not UTF-8,
 * and word wrapping for the messages. */
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
/* What a file on disk was when the text was read from it or saved to it:
 * a save first compares it with what is there now. */
struct tui_disk {
  int exists;
  long long size, mtime_ns;
  uint64_t hash;         /* tui_hash of its bytes */
  size_t len;
};
/* FNV-1a, 64 bits. */
uint64_t tui_hash(const void *p, size_t n);
/* The file at path, whose bytes are buf (n of them): stat it now. */
void tui_disk_of(const char *path, const char *buf, size_t n, struct tui_disk *d);
/* Has the file at path changed since d was taken?  0 no; 1 yes (another
 * size or content, removed, or created).  Size and modification time
 * decide when they are the same; when only the time differs the content
 * is read and compared (a `touch` is not a change). */
int tui_disk_changed(const char *path, const struct tui_disk *d);

/* Read a file into the text; on failure the text stays as it was.  d (may
 * be NULL) gets what the file was. */
int tui_text_load(struct tui_text *t, const char *path, struct tui_disk *d, char *err, size_t errn);
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
/* The next line holding needle, searching from line `from` in direction
 * dir (+1 or -1) and going on round the text's end: its index, with *byte
 * the match's offset in it and *wrapped set when the search went past an
 * end; -1 when no line holds it (or needle is empty). */
long tui_text_find(const struct tui_text *t, size_t from, int dir, const char *needle, size_t *byte,
                   int *wrapped);
/* Save atomically: a temporary file beside it, fsync, rename over the old
 * file, fsync of the directory -- the file on disk is always either the old
 * text or the new one.  Keeps the old file's permissions.  0, or -1 with
 * err. */
int tui_text_save(const struct tui_text *t, const char *path, struct tui_disk *d, char *err, size_t errn);

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
/* Wrap n code points into rows of at most w columns, breaking at spaces (a
 * word longer than a row is cut); the spaces at a break are dropped.  Row
 * r is s[start[r]] .. s[start[r] + len[r] - 1].  Returns the rows (at most
 * max; 1 for an empty text). */
int tui_wrap(const uint32_t *s, int n, int w, int *start, int *len, int max);

#endif
