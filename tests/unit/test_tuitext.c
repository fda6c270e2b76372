/* What the terminal edits and shows, without curses (src/host/tuitext.h): the
 * text's lines and edits, atomic save, the Cyrillic key map of table 3.4,
 * the ASCII stand-ins; and the machine-speed clock (src/host/pace.h). */
#include "suites.h"
#include "pace.h"
#include "screen.h"
#include "tuitext.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

static char *joined(const struct tui_text *t)
{
  size_t n;
  char *s = tui_text_join(t, &n);
  ck_assert_ptr_nonnull(s);
  ck_assert_uint_eq(strlen(s), n);
  return s;
}

static void roundtrip(const char *in)
{
  struct tui_text t;
  char err[128];
  tui_text_init(&t);
  ck_assert_int_eq(tui_text_set(&t, in, strlen(in), err, sizeof err), 0);
  char *out = joined(&t);
  ck_assert_str_eq(out, in);
  free(out);
  tui_text_free(&t);
}

START_TEST(text_roundtrip)
{
  roundtrip("");
  roundtrip("№1 M02 ^\n");
  roundtrip("№1 G04 X+2 ^\n№2 M02 ^");          /* no final line end */
  roundtrip("№1 G04 X+2 ^\r\n№2 M02 ^\r\n");    /* CRLF kept */
  roundtrip("\n\n;\n");
  roundtrip("; old Mac\r№1 G04 X+2 ^\r№2 M02 ^\r");   /* CR-only line ends kept */
}
END_TEST

START_TEST(text_lines_and_nul)
{
  struct tui_text t;
  char err[128];
  tui_text_init(&t);
  ck_assert_int_eq(tui_text_set(&t, "a\nbb\r\nccc", 9, err, sizeof err), 0);
  ck_assert_uint_eq(t.n, 3);
  ck_assert_str_eq(t.line[1], "bb\r");    /* a lone \r\n among \n line ends: the \r stays */
  char *s = joined(&t);
  ck_assert_str_eq(s, "a\nbb\r\nccc");
  free(s);
  ck_assert_int_eq(tui_text_set(&t, "a\0b\n", 4, err, sizeof err), -1);
  ck_assert_ptr_nonnull(strstr(err, "NUL"));
  ck_assert_uint_eq(t.n, 3);              /* unchanged */
  /* CR alone ends the lines of a file with no LF, as the compiler reads it */
  ck_assert_int_eq(tui_text_set(&t, "; c\r№1 M02\r", 12, err, sizeof err), 0);
  ck_assert_uint_eq(t.n, 2);
  ck_assert_str_eq(t.line[0], "; c");
  tui_text_free(&t);
}
END_TEST

START_TEST(text_edits_and_undo)
{
  struct tui_text t;
  char err[128];
  tui_text_init(&t);
  ck_assert_int_eq(tui_text_set(&t, "№1 G33 /А/ ^\n№2 M02 ^\n", strlen("№1 G33 /А/ ^\n№2 M02 ^\n"), err, sizeof err), 0);
  ck_assert_int_eq(tui_text_insert(&t, 1, "№3 G04 X+1 ^"), 0);
  char *s = joined(&t);
  ck_assert_str_eq(s, "№1 G33 /А/ ^\n№3 G04 X+1 ^\n№2 M02 ^\n");
  free(s);
  ck_assert_int_eq(tui_text_replace(&t, 0, "№1 G33 /Б/ ^"), 0);
  ck_assert_str_eq(t.line[0], "№1 G33 /Б/ ^");
  ck_assert_int_eq(tui_text_undo(&t), 0);
  ck_assert_str_eq(t.line[0], "№1 G33 /А/ ^");
  ck_assert_int_eq(tui_text_undo(&t), 0);          /* undo of the undo */
  ck_assert_str_eq(t.line[0], "№1 G33 /Б/ ^");
  ck_assert_int_eq(tui_text_delete(&t, 1), 0);
  ck_assert_uint_eq(t.n, 2);
  ck_assert_str_eq(t.line[1], "№2 M02 ^");
  ck_assert_int_eq(tui_text_delete(&t, 2), -1);    /* no such line */
  ck_assert_int_eq(tui_text_replace(&t, 5, "x"), -1);
  ck_assert_int_eq(tui_text_insert(&t, 3, "x"), -1);
  ck_assert_int_eq(tui_text_insert(&t, 2, "№9 M02 ^"), 0);   /* append */
  ck_assert_str_eq(t.line[2], "№9 M02 ^");
  tui_text_free(&t);
  tui_text_init(&t);
  ck_assert_int_eq(tui_text_undo(&t), -1);
  ck_assert_int_eq(tui_text_insert(&t, 0, "№1 M02 ^"), 0);   /* into an empty text */
  s = joined(&t);
  ck_assert_str_eq(s, "№1 M02 ^\n");
  free(s);
  tui_text_free(&t);
}
END_TEST

static char *slurp(const char *path)
{
  FILE *f = fopen(path, "rb");
  ck_assert_ptr_nonnull(f);
  static char b[4096];
  size_t n = fread(b, 1, sizeof b - 1, f);
  b[n] = 0;
  fclose(f);
  return b;
}

START_TEST(text_save_atomic)
{
  char dir[] = "/tmp/s42-tuitext-XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char path[256], link[256], err[512], bad[256];
  snprintf(path, sizeof path, "%s/p.kp", dir);
  snprintf(link, sizeof link, "%s/link.kp", dir);
  struct tui_text t;
  tui_text_init(&t);
  ck_assert_int_eq(tui_text_set(&t, "№1 M02 ^\n", strlen("№1 M02 ^\n"), err, sizeof err), 0);
  ck_assert_int_eq(tui_text_save(&t, path, NULL, err, sizeof err), 0);
  ck_assert_str_eq(slurp(path), "№1 M02 ^\n");
  /* the old file's permissions stay */
  ck_assert_int_eq(chmod(path, 0640), 0);
  ck_assert_int_eq(tui_text_insert(&t, 0, "№2 G04 X+1 ^"), 0);
  ck_assert_int_eq(tui_text_save(&t, path, NULL, err, sizeof err), 0);
  struct stat st;
  ck_assert_int_eq(stat(path, &st), 0);
  ck_assert_int_eq(st.st_mode & 0777, 0640);
  ck_assert_str_eq(slurp(path), "№2 G04 X+1 ^\n№1 M02 ^\n");
  /* through a symbolic link: the program changes, the link stays a link */
  ck_assert_int_eq(symlink("p.kp", link), 0);
  ck_assert_int_eq(tui_text_replace(&t, 0, "№3 G04 X+2 ^"), 0);
  ck_assert_int_eq(tui_text_save(&t, link, NULL, err, sizeof err), 0);
  ck_assert_int_eq(lstat(link, &st), 0);
  ck_assert(S_ISLNK(st.st_mode));
  ck_assert_str_eq(slurp(path), "№3 G04 X+2 ^\n№1 M02 ^\n");
  /* a failure leaves the old file and no temporary behind */
  snprintf(bad, sizeof bad, "%s/no/such/dir.kp", dir);
  ck_assert_int_eq(tui_text_save(&t, bad, NULL, err, sizeof err), -1);
  ck_assert_ptr_nonnull(strstr(err, "temporary"));
  ck_assert_int_eq(tui_text_save(&t, dir, NULL, err, sizeof err), -1);   /* a directory */
  ck_assert_ptr_nonnull(strstr(err, "not a regular file"));
  ck_assert_int_eq(unlink(link), 0);
  ck_assert_int_eq(unlink(path), 0);
  ck_assert_int_eq(rmdir(dir), 0);   /* empty: no temporary file was left */
  /* loading a missing file says so and keeps the text */
  ck_assert_int_eq(tui_text_load(&t, path, NULL, err, sizeof err), -1);
  ck_assert_ptr_nonnull(strstr(err, "No such file"));
  ck_assert_uint_eq(t.n, 2);
  tui_text_free(&t);
}
END_TEST

/* The rows tui_wrap makes of s in w columns, joined by '|'. */
static const char *wrap(const char *s, int w)
{
  static char out[512];
  uint32_t cp[256];
  int st[256], ln[256];
  int n = screen_decode(s, cp, 256), rows = tui_wrap(cp, n, w, st, ln, 256);
  char *p = out;
  for (int r = 0; r < rows; r++) {
    if (r)
      *p++ = '|';
    for (int c = 0; c < ln[r]; c++)
      p += tui_utf8(cp[st[r] + c], p);
  }
  *p = 0;
  return out;
}

START_TEST(wrap_at_words)
{
  ck_assert_str_eq(wrap("drill.kp: 61 lines, 0 errors, 0 warnings", 16), "drill.kp: 61|lines, 0 errors,|0 warnings");
  ck_assert_str_eq(wrap("fits", 10), "fits");
  ck_assert_str_eq(wrap("", 10), "");
  ck_assert_str_eq(wrap("ab cd", 2), "ab|cd");               /* the space at the break goes */
  ck_assert_str_eq(wrap("abcdefgh ij", 4), "abcd|efgh|ij");    /* a word longer than a row is cut */
  ck_assert_str_eq(wrap("Пуск: the cycle starts", 11), "Пуск: the|cycle|starts");   /* columns, not bytes */
  ck_assert_str_eq(wrap("a  b", 1), "a|b");
  ck_assert_str_eq(wrap("   lead", 10), "lead");
  uint32_t cp[8];
  int st[2], ln[2], n = screen_decode("aa bb cc dd", cp, 8);
  ck_assert_int_eq(tui_wrap(cp, n, 2, st, ln, 2), 2);         /* at most max rows */
}
END_TEST

START_TEST(find_in_text)
{
  struct tui_text t;
  char err[64];
  const char *src = "№1 G27 /А/ ^\n№2 G28 /1:9/ R1 ^\n№3 G04 ^\n№4 G28 /1:5/ R2 ^\n";
  tui_text_init(&t);
  ck_assert_int_eq(tui_text_set(&t, src, strlen(src), err, sizeof err), 0);
  size_t b;
  int wr;
  ck_assert_int_eq(tui_text_find(&t, 0, 1, "G28", &b, &wr), 1);
  ck_assert_uint_eq(b, strlen("№2 "));
  ck_assert_int_eq(wr, 0);
  ck_assert_int_eq(tui_text_find(&t, 2, 1, "G28", &b, &wr), 3);
  ck_assert_int_eq(tui_text_find(&t, 0, 1, "/А/", &b, &wr), 0);   /* from the line itself */
  ck_assert_int_eq(wr, 0);
  ck_assert_int_eq(tui_text_find(&t, 2, 1, "G27", &b, &wr), 0);   /* on round the end */
  ck_assert_int_eq(wr, 1);
  ck_assert_int_eq(tui_text_find(&t, 2, -1, "G28", &b, &wr), 1);  /* backwards */
  ck_assert_int_eq(wr, 0);
  ck_assert_int_eq(tui_text_find(&t, 0, -1, "G28", &b, &wr), 3);  /* backwards round the top */
  ck_assert_int_eq(wr, 1);
  ck_assert_int_eq(tui_text_find(&t, 0, 1, "G99", &b, &wr), -1);
  ck_assert_int_eq(tui_text_find(&t, 0, 1, "", &b, &wr), -1);
  ck_assert_int_eq(tui_text_find(&t, 99, 1, "G04", &b, &wr), 2);  /* a cursor past the end */
  tui_text_free(&t);
  tui_text_init(&t);
  ck_assert_int_eq(tui_text_find(&t, 0, 1, "G04", &b, &wr), -1);  /* an empty text */
}
END_TEST

START_TEST(disk_change_noticed)
{
  char dir[] = "/tmp/s42-tuidisk-XXXXXX";
  ck_assert_ptr_nonnull(mkdtemp(dir));
  char path[256], err[512];
  snprintf(path, sizeof path, "%s/p.kp", dir);
  struct tui_text t;
  struct tui_disk d;
  tui_text_init(&t);
  ck_assert_int_eq(tui_text_set(&t, "№1 M02 ^\n", strlen("№1 M02 ^\n"), err, sizeof err), 0);
  /* a new file: not there, and still not there */
  tui_disk_of(path, "", 0, &d);
  ck_assert_int_eq(d.exists, 0);
  ck_assert_int_eq(tui_disk_changed(path, &d), 0);
  /* saved: what is on disk is what was written */
  ck_assert_int_eq(tui_text_save(&t, path, &d, err, sizeof err), 0);
  ck_assert_int_eq(d.exists, 1);
  ck_assert_int_eq(d.size, (long long)strlen("№1 M02 ^\n"));
  ck_assert_int_eq(tui_disk_changed(path, &d), 0);
  /* read back: the same */
  struct tui_disk r;
  ck_assert_int_eq(tui_text_load(&t, path, &r, err, sizeof err), 0);
  ck_assert(r.hash == d.hash && r.size == d.size && r.mtime_ns == d.mtime_ns);
  /* another program changes it, to another size */
  FILE *f = fopen(path, "a");
  ck_assert_ptr_nonnull(f);
  fputs("; more\n", f);
  fclose(f);
  ck_assert_int_eq(tui_disk_changed(path, &r), 1);
  /* the same size, other bytes, another time */
  ck_assert_int_eq(tui_text_load(&t, path, &r, err, sizeof err), 0);
  f = fopen(path, "r+");
  ck_assert_ptr_nonnull(f);
  fputs("№2", f);
  fclose(f);
  struct timespec ts[2] = {{0, UTIME_OMIT}, {1000000000, 0}};
  ck_assert_int_eq(utimensat(AT_FDCWD, path, ts, 0), 0);
  ck_assert_int_eq(tui_disk_changed(path, &r), 1);
  /* only the time changed (touch): the bytes say it is the same */
  ck_assert_int_eq(tui_text_load(&t, path, &r, err, sizeof err), 0);
  struct timespec tt[2] = {{0, UTIME_OMIT}, {2000000000, 0}};
  ck_assert_int_eq(utimensat(AT_FDCWD, path, tt, 0), 0);
  ck_assert_int_eq(tui_disk_changed(path, &r), 0);
  /* removed */
  ck_assert_int_eq(unlink(path), 0);
  ck_assert_int_eq(tui_disk_changed(path, &r), 1);
  ck_assert_int_eq(rmdir(dir), 0);
  ck_assert(tui_hash("a", 1) != tui_hash("b", 1));
  tui_text_free(&t);
}
END_TEST

START_TEST(cyr_table_3_4)
{
  /* every row of the seed's table 3.4 */
  static const char keys[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZ*:+(%)";
  static const uint32_t want[] = {
    0x410, 0x411, 0x426, 0x414, 0x415, 0x424, 0x413, 0x425, 0x418, 0x419, 0x41A, 0x41B, 0x41C,
    0x41D, 0x41E, 0x41F, 0x42F, 0x420, 0x421, 0x422, 0x423, 0x416, 0x412, 0x42C, 0x42B, 0x417,
    0x42E, 0x428, 0x42D, 0x429, 0x427, 0x42A,
  };
  for (size_t i = 0; keys[i]; i++)
    ck_assert_uint_eq(tui_cyr_key((uint32_t)keys[i]), want[i]);
  ck_assert_uint_eq(tui_cyr_key('w'), 0x412);   /* capitals only */
  ck_assert_uint_eq(tui_cyr_key('7'), '7');     /* digits and the rest stay */
  ck_assert_uint_eq(tui_cyr_key('/'), '/');
  ck_assert_uint_eq(tui_cyr_key(' '), ' ');
}
END_TEST

START_TEST(ascii_stand_ins)
{
  uint32_t cp[32];
  int n = screen_decode("ЗАТОЧКА Ї №1 ─│┌ 中", cp, 32);
  char out[33];
  for (int i = 0; i < n; i++)
    out[i] = tui_ascii(cp[i]);
  out[n] = 0;
  ck_assert_str_eq(out, "ZATOCKA I N1 -|+ ?");
  ck_assert_int_eq(tui_ascii(0x1F), '?');
  ck_assert_int_eq(tui_ascii('~'), '~');
  ck_assert_int_eq(tui_ascii(0x2026), '$');   /* … where a line is cut */
  ck_assert_int_eq(tui_ascii(0x2265), '>');   /* ≥ of an estimate */
  ck_assert_int_eq(tui_ascii(0x2192), '>');   /* → of a cycle exit */
  char u[4];
  ck_assert_int_eq(tui_utf8(0x416, u), 2);
  ck_assert_int_eq(memcmp(u, "Ж", 2), 0);
  ck_assert_int_eq(tui_utf8(0x2116, u), 3);
  ck_assert_int_eq(memcmp(u, "№", 3), 0);
}
END_TEST

START_TEST(pace_clock)
{
  struct pace p;
  pace_start(&p, 10.0);
  double a = pace_now(&p);
  ck_assert(a >= 10.0 && a < 10.5);
  ck_assert(pace_ahead(&p, 20.0) > 9.0);
  ck_assert(pace_ahead(&p, 5.0) < 0);
  pace_hold(&p, 1);
  double h = pace_now(&p);
  usleep(20000);
  ck_near(pace_now(&p), h, 1e-12);     /* held: the clock stands */
  pace_hold(&p, 0);
  double r = pace_now(&p);
  ck_assert(r >= h && r < h + 0.01);   /* and goes on from there */
  pace_sleep_until(&p, r + 0.02);
  ck_assert(pace_now(&p) >= r + 0.02);
}
END_TEST

Suite *suite_tuitext(void)
{
  Suite *s = suite_create("tuitext");
  TCase *c = tcase_create("tuitext");
  tcase_add_test(c, text_roundtrip);
  tcase_add_test(c, text_lines_and_nul);
  tcase_add_test(c, text_edits_and_undo);
  tcase_add_test(c, text_save_atomic);
  tcase_add_test(c, wrap_at_words);
  tcase_add_test(c, find_in_text);
  tcase_add_test(c, disk_change_noticed);
  tcase_add_test(c, cyr_table_3_4);
  tcase_add_test(c, ascii_stand_ins);
  tcase_add_test(c, pace_clock);
  suite_add_tcase(s, c);
  return s;
}
