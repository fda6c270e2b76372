/* The M15 restart state (src/state.h) and the careful file handling under
 * it (src/atomic.h): a --state that is not a state (never replaced), the
 * temporary file a killed save leaves (removed by the next), and the reads
 * that refuse a FIFO or a device (standard input's pipe allowed). */
#include "suites.h"
#include "atomic.h"
#include "kp.h"
#include "session.h"
#include "state.h"
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

/* A restart point inside a sub called from the main program. */
static const char prog[] =
  "№10 R100+R100+1 T11+R100 M15 ^\n"
  "№11 G04 X+1 M17 ^\n"
  "№1 R100+0 F1000 M18 /ПРОХІД ((R100/ ^\n"
  "№2 G29 /ПРОХІД((R100// ^\n"
  "№3 G01 X+1000 L10 H3 ^\n"
  "№4 M02 ^\n";

static struct tprog t;
static struct session *s;
static char dir[64], path[128];
static uint64_t hash;

static void fresh(void)
{
  sess_init(s, &t.p);
}

/* Run until the k-th start of an M15 block (k from 1). */
static void to_m15(int k)
{
  static uint8_t watch[16];
  for (size_t b = 0; b < t.p.nblocks; b++)
    watch[b] = (kp_attr(&t.p, b)->m >> 15) & 1;
  s->vm.watch = watch;
  for (int seen = 0; seen < k;) {
    enum sess_ev ev = sess_run(s);
    ck_assert_int_eq(ev, SE_START);
    seen += watch[s->vm.cur];
  }
}

static void setup(void)
{
  s = calloc(1, sizeof *s);
  tp_compile(&t, prog);
  ck_assert_msg(t.rc == 0, "does not compile:\n%s", tp_diags(&t.d));
  hash = state_hash(prog, strlen(prog));
  snprintf(dir, sizeof dir, "/tmp/s42-state.XXXXXX");
  ck_assert_ptr_nonnull(mkdtemp(dir));
  snprintf(path, sizeof path, "%s/p.state", dir);
  fresh();
  to_m15(2);
  char err[400];
  ck_assert_msg(state_save(s, path, hash, err, sizeof err) == 0, "%s", err);
  fresh();
}

static void teardown(void)
{
  char cmd[160];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  ck_assert_int_eq(system(cmd), 0);
  tp_free(&t);
  free(s);
}

/* ---- --state over something that is not a state ---- */

static void write_file(const char *p, const char *text)
{
  FILE *f = fopen(p, "wb");
  ck_assert_ptr_nonnull(f);
  fputs(text, f);
  fclose(f);
}

static char *slurp(const char *p)
{
  char *b = NULL, err[200];
  size_t n;
  ck_assert_msg(file_read_all(p, FILE_REGULAR, 1 << 20, &b, &n, err, sizeof err) == 0, "%s", err);
  return b;
}

START_TEST(save_never_replaces_a_non_state)
{
  char p[160], err[400];
  fresh();
  to_m15(1);
  /* a program given as --state stays the program */
  snprintf(p, sizeof p, "%s/self.kp", dir);
  write_file(p, prog);
  ck_assert_int_eq(state_save(s, p, hash, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "self.kp is not an s42 restart state: it is not replaced"), "%s", err);
  char *b = slurp(p);
  ck_assert_str_eq(b, prog);
  free(b);
  /* a file shorter than the magic */
  write_file(p, "S42");
  ck_assert_int_eq(state_save(s, p, hash, err, sizeof err), -1);
  /* a FIFO: refused at once, not waited on */
  snprintf(p, sizeof p, "%s/fifo", dir);
  ck_assert_int_eq(mkfifo(p, 0600), 0);
  ck_assert_int_eq(state_save(s, p, hash, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "is a FIFO, not a restart state"), "%s", err);
  struct stat st;
  ck_assert_int_eq(stat(p, &st), 0);
  ck_assert(S_ISFIFO(st.st_mode));
  /* a directory */
  ck_assert_int_eq(state_save(s, dir, hash, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "is a directory, not a restart state"), "%s", err);
  /* an empty file holds nothing to lose; an old state is replaced */
  snprintf(p, sizeof p, "%s/empty.state", dir);
  write_file(p, "");
  ck_assert_msg(state_save(s, p, hash, err, sizeof err) == 0, "%s", err);
  ck_assert_msg(state_save(s, p, hash, err, sizeof err) == 0, "%s", err);
  ck_assert_int_eq(stat(p, &st), 0);
  ck_assert_int_gt(st.st_size, 8000);
}
END_TEST

/* ---- the temporary file of a killed save ---- */

static int exists(const char *name)
{
  char p[200];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  return access(p, F_OK) == 0;
}

START_TEST(stale_temporary_removed)
{
  char p[200], err[400];
  /* left by a killed save: removed; others kept */
  static const char *const gone[] = {"p.state.tmpAbC123", "p.state.tmp000000"};
  static const char *const kept[] = {"p.state.tmpAbC12", "p.state.tmpAbC1234", "p.state.tmpAb-123",
                                     "q.state.tmpAbC123", "p.state.tmpzzzzzz.kp"};
  for (size_t i = 0; i < 2; i++) {
    snprintf(p, sizeof p, "%s/%s", dir, gone[i]);
    write_file(p, "half a state");
  }
  for (size_t i = 0; i < 5; i++) {
    snprintf(p, sizeof p, "%s/%s", dir, kept[i]);
    write_file(p, "x");
  }
  /* one a live writer holds (its flock): kept */
  snprintf(p, sizeof p, "%s/p.state.tmpLIVE01", dir);
  write_file(p, "being written");
  int fd = open(p, O_RDONLY);
  ck_assert_int_ge(fd, 0);
  ck_assert_int_eq(flock(fd, LOCK_EX), 0);
  /* a directory of that name: kept */
  snprintf(p, sizeof p, "%s/p.state.tmpDIR001", dir);
  ck_assert_int_eq(mkdir(p, 0700), 0);
  fresh();
  to_m15(1);
  ck_assert_msg(state_save(s, path, hash, err, sizeof err) == 0, "%s", err);
  for (size_t i = 0; i < 2; i++)
    ck_assert_msg(!exists(gone[i]), "%s is still there", gone[i]);
  for (size_t i = 0; i < 5; i++)
    ck_assert_msg(exists(kept[i]), "%s was removed", kept[i]);
  ck_assert(exists("p.state.tmpLIVE01"));
  ck_assert(exists("p.state.tmpDIR001"));
  close(fd);
  /* unlocked now: the next save takes it */
  ck_assert_msg(state_save(s, path, hash, err, sizeof err) == 0, "%s", err);
  ck_assert(!exists("p.state.tmpLIVE01"));
  /* and a save leaves no temporary file of its own */
  snprintf(p, sizeof p, "%s/p.state.tmpDIR001", dir);
  ck_assert_int_eq(rmdir(p), 0);
  snprintf(p, sizeof p, "ls '%s' | grep -q '^p\\.state\\.tmp[A-Za-z0-9]\\{6\\}$'", dir);
  ck_assert_int_ne(system(p), 0);
}
END_TEST

/* ---- reading: only regular files (and standard input's pipe) ---- */

START_TEST(read_refuses_fifo_and_devices)
{
  char p[160], err[400], *b;
  size_t n;
  snprintf(p, sizeof p, "%s/fifo", dir);
  ck_assert_int_eq(mkfifo(p, 0600), 0);
  /* no writer: the open would block without O_NONBLOCK */
  ck_assert_int_eq(file_read_all(p, FILE_OR_STDIN, 100, &b, &n, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "fifo: is a FIFO, not a regular file"), "%s", err);
  /* a writer that never writes: the read would block */
  int w = open(p, O_RDWR);
  ck_assert_int_ge(w, 0);
  ck_assert_int_eq(file_read_all(p, FILE_REGULAR, 100, &b, &n, err, sizeof err), -1);
  close(w);
  ck_assert_int_eq(file_read_all("/dev/zero", FILE_OR_STDIN, 100, &b, &n, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "/dev/zero: is a character device, not a regular file"), "%s", err);
  ck_assert_int_eq(file_read_all(dir, FILE_REGULAR, 100, &b, &n, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "is a directory, not a file"), "%s", err);
  ck_assert_int_eq(file_check_read(p, FILE_OR_STDIN, err, sizeof err), -1);
  ck_assert_int_eq(file_check_read("/no/such/file", FILE_REGULAR, err, sizeof err), 0);
  ck_assert_int_eq(file_check_read(path, FILE_REGULAR, err, sizeof err), 0);
  /* a state on a FIFO: refused the same way */
  ck_assert_int_eq(state_load(s, p, hash, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "no restart state: ") && strstr(err, "is a FIFO"), "%s", err);
}
END_TEST

START_TEST(read_sizes)
{
  char p[160], err[400], *b;
  size_t n;
  snprintf(p, sizeof p, "%s/ten", dir);
  write_file(p, "0123456789");
  ck_assert_int_eq(file_read_all(p, FILE_REGULAR, 10, &b, &n, err, sizeof err), 0);
  ck_assert_uint_eq(n, 10);
  ck_assert_str_eq(b, "0123456789");
  free(b);
  ck_assert_int_eq(file_read_all(p, FILE_REGULAR, 9, &b, &n, err, sizeof err), -2);
  ck_assert_msg(strstr(err, "too large: at most 9 bytes are read"), "%s", err);
  snprintf(p, sizeof p, "%s/nothing", dir);
  write_file(p, "");
  ck_assert_int_eq(file_read_all(p, FILE_REGULAR, 9, &b, &n, err, sizeof err), 0);
  ck_assert_uint_eq(n, 0);
  ck_assert_str_eq(b, "");
  free(b);
}
END_TEST

START_TEST(read_stdin_pipe)
{
  /* standard input is a pipe (Check runs each test in its own process) */
  int fds[2];
  ck_assert_int_eq(pipe(fds), 0);
  ck_assert_int_eq(dup2(fds[0], STDIN_FILENO), STDIN_FILENO);
  close(fds[0]);
  ck_assert_int_eq(write(fds[1], "key PUSK\n", 9), 9);
  close(fds[1]);
  char err[400], *b;
  size_t n;
  ck_assert_msg(file_read_all("/dev/stdin", FILE_OR_STDIN, 100, &b, &n, err, sizeof err) == 0, "%s", err);
  ck_assert_str_eq(b, "key PUSK\n");
  free(b);
  /* a state is never read from a pipe */
  ck_assert_int_eq(pipe(fds), 0);
  ck_assert_int_eq(dup2(fds[0], STDIN_FILENO), STDIN_FILENO);
  close(fds[0]);
  ck_assert_int_eq(file_read_all("/dev/stdin", FILE_REGULAR, 100, &b, &n, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "is a FIFO, not a regular file"), "%s", err);
  close(fds[1]);
}
END_TEST

Suite *suite_state(void)
{
  Suite *s_ = suite_create("state");
  TCase *tc = tcase_create("files");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, save_never_replaces_a_non_state);
  tcase_add_test(tc, stale_temporary_removed);
  tcase_add_test(tc, read_refuses_fifo_and_devices);
  tcase_add_test(tc, read_sizes);
  tcase_add_test(tc, read_stdin_pipe);
  suite_add_tcase(s_, tc);
  return s_;
}
