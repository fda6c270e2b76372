/* The M15 restart state (src/core/state.h) against hostile files: a state saved
 * and restored, every field edited by hand with its checksum recomputed
 * (each refused, naming the field), a loop of random edits that must be
 * refused or run safely, a --state that is not a state (never replaced),
 * the temporary file a killed save leaves (removed by the next), two
 * processes saving one file at once (neither loses a save), and the
 * careful reads of src/core/atomic.h (a FIFO, a device, standard input). */
#include "suites.h"
#include "atomic.h"
#include "kp.h"
#include "session.h"
#include "state.h"
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* A restart point inside a sub called from the main program, with array
 * writes, a G29 display and an M18 directive: every kind of field. */
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
static struct state_header good_h;
static struct state_payload good;   /* saved at the second start of N10 */

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

static void read_good(void)
{
  FILE *f = fopen(path, "rb");
  ck_assert_ptr_nonnull(f);
  ck_assert_int_eq(fread(&good_h, sizeof good_h, 1, f), 1);
  ck_assert_int_eq(fread(&good, sizeof good, 1, f), 1);
  ck_assert_int_eq(fgetc(f), EOF);
  fclose(f);
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
  read_good();
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

/* Restore a payload (its checksum recomputed): 0 or -1 with err. */
static int restore(const struct state_payload *pl, char *err, size_t n)
{
  static unsigned char buf[sizeof(struct state_header) + sizeof(struct state_payload)];
  struct state_header h = good_h;
  h.sum = state_hash(pl, sizeof *pl);
  memcpy(buf, &h, sizeof h);
  memcpy(buf + sizeof h, pl, sizeof *pl);
  fresh();
  return state_restore(s, buf, sizeof buf, "p.state", hash, err, n);
}

static enum sess_ev run_out(uint64_t budget)
{
  s->vm.watch = NULL;
  s->vm.max_blocks = s->vm.blocks + budget;
  enum sess_ev ev;
  while ((ev = sess_run(s)) == SE_START)
    ;
  return ev;
}

START_TEST(saved_and_restored)
{
  /* the whole run, and the run restarted from the second M15 */
  ck_assert_int_eq(run_out(1000), SE_END);
  double r100 = s->vm.reg[100];
  int64_t x = s->m.pos[0];
  double tt = s->m.t;
  char err[400];
  fresh();
  ck_assert_msg(state_load(s, path, hash, err, sizeof err) == 0, "%s", err);
  ck_assert_int_eq(s->vm.depth, 1);
  ck_assert_int_eq(s->vm.arr[0].ptr, 1);
  ck_assert_int_eq(s->scr.np3, 1);
  ck_assert_int_ne(s->directive, 0);
  ck_assert_int_eq(run_out(1000), SE_END);
  ck_near(s->vm.reg[100], r100, 0);
  ck_assert_int_eq(s->m.pos[0], x);
  ck_near(s->m.t, tt, 1e-9);
  ck_assert_int_eq(s->vm.arr[0].len, 3);
}
END_TEST

/* ---- every field edited by hand ---- */

#define EDIT(name, body) static void name(struct state_payload *p) { body; }
EDIT(e_block_past, p->block = 99)
EDIT(e_block_no_m15, p->block = 1)
EDIT(e_pc, p->pc += 1)
EDIT(e_blocks, p->blocks = UINT64_MAX)
EDIT(e_r_nan, p->reg[5] = NAN)
EDIT(e_r_big, p->reg[113] = 1e8)
EDIT(e_d1, p->reg[REG_D1] = -1)
EDIT(e_tk, p->reg[REG_TK] = INFINITY)
EDIT(e_ug, p->reg[REG_UG] = -1e7)
EDIT(e_f_big, p->reg[REG_F] = 6001)
EDIT(e_f_frac, p->reg[REG_F] = 10.5)
EDIT(e_unused, p->reg[120] = 1)
EDIT(e_ptr_neg, p->arr[0].ptr = -3)
EDIT(e_ptr_big, p->arr[1].ptr = 16)
EDIT(e_len, p->arr[1].len = 99)
EDIT(e_cell_nan, p->arr[0].cell[0] = NAN)
EDIT(e_cell_big, p->arr[0].cell[0] = 1e7)
EDIT(e_cell_past, p->arr[0].cell[9] = 5)
EDIT(e_depth_big, p->depth = 9)
EDIT(e_depth_neg, p->depth = -1)
EDIT(e_depth_0, p->depth = 0)
EDIT(e_ret_0, p->frames[0].ret = 0)
EDIT(e_ret_far, p->frames[0].ret = 1u << 30)
EDIT(e_ret_off, p->frames[0].ret -= 1)
EDIT(e_start, p->frames[0].start += 1)
EDIT(e_fblock, p->frames[0].block = 0)
EDIT(e_left, p->frames[0].left = 30000)
EDIT(e_saved, p->frames[0].saved = NAN)
EDIT(e_jflag, p->frames[0].jflag = 2)
EDIT(e_pos, p->pos[1] = INT64_MIN)
EDIT(e_pos_big, p->pos[3] = STATE_POS_MAX + 1)
EDIT(e_t_nan, p->t = NAN)
EDIT(e_t_neg, p->t = -1)
EDIT(e_t_inf, p->t = INFINITY)
EDIT(e_wheel, p->wheel = 3)
EDIT(e_override, p->override_pct = 151)
EDIT(e_ovr_switch, p->override_allowed = 2)
EDIT(e_corr_switch, p->corr_allowed = -1)
EDIT(e_nplug, p->nplug = 9)
EDIT(e_plug_noname, p->nplug = 1)
EDIT(e_plug_unterminated, p->nplug = 1; memset(p->plug[0].name, 'x', sizeof p->plug[0].name))
EDIT(e_plug_len, p->nplug = 1; strcpy(p->plug[0].name, "oscillation"); p->plug[0].len = 513)
EDIT(e_plug_twice, p->nplug = 2; strcpy(p->plug[0].name, "oscillation"); strcpy(p->plug[1].name, "oscillation"))
EDIT(e_plug_missing, p->nplug = 1; strcpy(p->plug[0].name, "nosuch"))
EDIT(e_p3, p->p3 = 2)
EDIT(e_np3, p->np3 = 15)
EDIT(e_np3_neg, p->np3 = -1)
EDIT(e_p3_reg, p->p3l[0].reg = 114)
EDIT(e_p3_ch, p->p3l[0].ch[3] = 0x110000)
EDIT(e_p3_surrogate, p->p3l[0].ch[0] = 0xD800)
EDIT(e_directive, p->directive = 12345)
EDIT(e_dirtext, strcpy(p->dirtext, "ІНШЕ"))
EDIT(e_dirtext_open, memset(p->dirtext, 'x', sizeof p->dirtext))
EDIT(e_dirtext_utf8, p->directive = 0; strcpy(p->dirtext, "\xff\xfe"))
EDIT(e_hash, p->prog_hash ^= 1)
#undef EDIT

static const struct {
  void (*edit)(struct state_payload *);
  const char *want;
} edits[] = {
  {e_block_past, "restart block is index 99, but the program has 6 blocks"},
  {e_block_no_m15, "restart block (line 2, N11) has no M15"},
  {e_pc, "code address is"},
  {e_blocks, "count of executed blocks is 18446744073709551615, over 2^53"},
  {e_r_nan, "R5 is nan, not -9999999..9999999"},
  {e_r_big, "R113 is 100000000, not -9999999..9999999"},
  {e_d1, "D1 is -1, not 0..400000"},
  {e_tk, "TK is inf"},
  {e_ug, "UG is -10000000"},
  {e_f_big, "F is 6001, not 0..6000"},
  {e_f_frac, "F is 10.5, not a whole number"},
  {e_unused, "unused register 120 is 1"},
  {e_ptr_neg, "the state's array 1 pointer is -3, not 0-15"},
  {e_ptr_big, "array 2 pointer is 16, not 0-15"},
  {e_len, "array 2 length is 99, not 0-15"},
  {e_cell_nan, "array 1 cell 0 is nan"},
  {e_cell_big, "array 1 cell 0 is 10000000"},
  {e_cell_past, "array 1 cell 9 is 5, past the array's length 1"},
  {e_depth_big, "sub call depth is 9, not 0-8"},
  {e_depth_neg, "sub call depth is -1, not 0-8"},
  {e_depth_0, "restart block N10 is not in the main program the call stack ends in"},
  {e_ret_0, "sub call 1 returns to code address 0"},
  {e_ret_far, "sub call 1 returns to code address 1073741824"},
  {e_ret_off, "which does not follow a call of the sub"},
  {e_start, "which does not follow a call of the sub"},
  {e_fblock, "sub call 1 is made from block index 0, not from a block of the main program"},
  {e_left, "sub call 1 repeats left is 30000, not 0-29999"},
  {e_saved, "sub call 1 saved F is nan"},
  {e_jflag, "sub call 1 jump condition is 2, not 0-1"},
  {e_pos, "Y position is -9223372036854775808 discretes, beyond +-9007199254740992"},
  {e_pos_big, "A position is 9007199254740993 discretes"},
  {e_t_nan, "time is nan, not 0..1e+15"},
  {e_t_neg, "time is -1"},
  {e_t_inf, "time is inf"},
  {e_wheel, "wheel state is 3, not 0-2"},
  {e_override, "feed override is 151, not 0-150"},
  {e_ovr_switch, "M25/M26 override switch is 2"},
  {e_corr_switch, "M22/M23 correction switch is -1"},
  {e_nplug, "plugin count is 9, not 0-8"},
  {e_plug_noname, "plugin 1's name is empty"},
  {e_plug_unterminated, "plugin 1's name is not terminated"},
  {e_plug_len, "oscillation plugin's record is 513 bytes, over its 512-byte buffer"},
  {e_plug_twice, "oscillation plugin's record comes twice"},
  {e_plug_missing, "the restart state needs the nosuch plugin, which is not loaded"},
  {e_p3, "P3 display switch is 2, not 0-1"},
  {e_np3, "G29 line count is 15, not 0-14"},
  {e_np3_neg, "G29 line count is -1"},
  {e_p3_reg, "G29 line 1 parameter is 114, not -1..113"},
  {e_p3_ch, "G29 line 1 holds U+110000, not a character"},
  {e_p3_surrogate, "G29 line 1 holds U+D800"},
  {e_directive, "directive is text 12345, which no M18 of this program shows"},
  {e_dirtext, "directive text is not that of its M18"},
  {e_dirtext_open, "directive text is not terminated"},
  {e_dirtext_utf8, "directive text is not UTF-8"},
  {e_hash, "the program text changed since the restart point was saved in p.state"},
};

START_TEST(edited_field_refused)
{
  struct state_payload pl = good;
  edits[_i].edit(&pl);
  char err[400] = "";
  int r = restore(&pl, err, sizeof err);
  ck_assert_msg(r == -1, "edit %d (%s) was accepted", _i, edits[_i].want);
  ck_assert_msg(strstr(err, edits[_i].want) != NULL, "edit %d: expected '%s' in '%s'", _i, edits[_i].want, err);
  /* the refused state left the machine as it was, except a plugin's name
   * (checked last, when the rest was taken) */
  if (edits[_i].edit != e_plug_missing) {
    ck_assert_uint_eq(s->vm.pc, t.p.entry);
    ck_assert_int_eq(s->vm.depth, 0);
    ck_near(s->m.t, 0, 0);
  }
}
END_TEST

START_TEST(unedited_copy_accepted)
{
  struct state_payload pl = good;
  char err[400];
  ck_assert_msg(restore(&pl, err, sizeof err) == 0, "%s", err);
  ck_assert_int_eq(run_out(1000), SE_END);
}
END_TEST

/* ---- random edits: refused, or a run that stays sane ---- */

static uint64_t rng = 0x9E3779B97F4A7C15ULL;
static uint64_t next(void)
{
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return rng;
}

START_TEST(random_edits_refused_or_safe)
{
  static const double special[] = {NAN, INFINITY, -INFINITY, -1, 1e300, 9999999, 10000000, 0.5, -0.0};
  static const int32_t ints[] = {-1, 0, 1, 2, 14, 15, 16, 150, 151, INT32_MIN, INT32_MAX};
  unsigned accepted = 0;
  char err[400];
  for (int it = 0; it < 4000; it++) {
    struct state_payload pl = good;
    unsigned char *b = (unsigned char *)&pl;
    int edits_n = 1 + (int)(next() % 3);
    for (int e = 0; e < edits_n; e++) {
      /* skip the hash: a changed hash is always refused and proves nothing */
      size_t off = sizeof pl.prog_hash + next() % (sizeof pl - sizeof pl.prog_hash);
      switch (next() % 4) {
      case 0: b[off] ^= (unsigned char)(1u << (next() % 8)); break;
      case 1: b[off] = (unsigned char)next(); break;
      case 2: {
        off &= ~(size_t)7;
        double d = special[next() % (sizeof special / sizeof *special)];
        if (off >= sizeof pl.prog_hash && off + 8 <= sizeof pl)
          memcpy(b + off, &d, 8);
        break;
      }
      default: {
        off &= ~(size_t)3;
        int32_t v = ints[next() % (sizeof ints / sizeof *ints)];
        if (off >= sizeof pl.prog_hash && off + 4 <= sizeof pl)
          memcpy(b + off, &v, 4);
      }
      }
    }
    if (restore(&pl, err, sizeof err) != 0) {
      ck_assert_msg(strstr(err, "the state's ") || strstr(err, "plugin"), "iteration %d: '%s'", it, err);
      continue;
    }
    accepted++;
    /* what was accepted runs like any program: to its end or a clean error */
    enum sess_ev ev = run_out(200);
    ck_assert_msg(ev == SE_END || ev == SE_ERROR, "iteration %d: event %d", it, ev);
    for (int a = 0; a < 2; a++) {
      ck_assert_int_ge(s->vm.arr[a].ptr, 0);
      ck_assert_int_le(s->vm.arr[a].ptr, KP_CELLS);
    }
    ck_assert(isfinite(s->m.t));
  }
  /* most edits land in bytes a restart does not read (padding, unused
   * cells, plugin buffers) or in values that are still in range */
  ck_assert_uint_gt(accepted, 100);
}
END_TEST

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
  ck_assert_int_eq(st.st_size, sizeof(struct state_header) + sizeof(struct state_payload));
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

/* Two runs saving one state file (`s42 tui c.kp` beside `s42 run c.kp`,
 * both on c.kp.state): each save first sweeps the temporary files of
 * killed saves, and must never take the other's live one.  Two processes
 * save the same file CONCURRENT_SAVES times each; every save must succeed,
 * and what is left is one whole state and no temporary file.  On a tmpfs
 * when there is one: the saves are fast there, so they meet more often. */
enum { CONCURRENT_SAVES = 4000, CONCURRENT_WRITERS = 2 };

START_TEST(concurrent_saves_keep_their_temporaries)
{
  char d[128], p[160], cmd[200], err[400];
  snprintf(d, sizeof d, "/dev/shm/s42-state.XXXXXX");
  if (!mkdtemp(d)) {
    snprintf(d, sizeof d, "%s/both", dir);
    ck_assert_int_eq(mkdir(d, 0700), 0);
  }
  snprintf(p, sizeof p, "%s/c.kp.state", d);
  fresh();
  to_m15(1);
  int fds[2];
  ck_assert_int_eq(pipe(fds), 0);
  pid_t pid[CONCURRENT_WRITERS];
  for (int w = 0; w < CONCURRENT_WRITERS; w++) {
    pid[w] = fork();
    ck_assert_int_ge(pid[w], 0);
    if (pid[w] == 0) {
      close(fds[0]);
      for (int i = 0; i < CONCURRENT_SAVES; i++)
        if (state_save(s, p, hash, err, sizeof err) != 0) {
          char msg[600];
          int len = snprintf(msg, sizeof msg, "writer %d, save %d of %d: %s\n", w + 1, i + 1, CONCURRENT_SAVES, err);
          ssize_t r = write(fds[1], msg, (size_t)len);
          (void)r;
          _exit(1);
        }
      _exit(0);
    }
  }
  close(fds[1]);
  char msgs[1300] = "";
  size_t got = 0;
  ssize_t r;
  while (got < sizeof msgs - 1 && (r = read(fds[0], msgs + got, sizeof msgs - 1 - got)) > 0)
    got += (size_t)r;
  msgs[got] = 0;
  close(fds[0]);
  int failed = 0;
  for (int w = 0; w < CONCURRENT_WRITERS; w++) {
    int st;
    ck_assert_int_eq(waitpid(pid[w], &st, 0), pid[w]);
    failed += !WIFEXITED(st) || WEXITSTATUS(st) != 0;
  }
  snprintf(cmd, sizeof cmd, "ls '%s' | grep -q '^c\\.kp\\.state\\.tmp'", d);
  int left = system(cmd) == 0;
  fresh();
  int loaded = state_load(s, p, hash, err, sizeof err);
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", d);
  ck_assert_int_eq(system(cmd), 0);
  ck_assert_msg(!failed, "%d of %d writers failed a save:\n%s", failed, CONCURRENT_WRITERS, msgs);
  ck_assert_msg(!left, "temporary files were left beside the state");
  ck_assert_msg(loaded == 0, "%s", err);
}
END_TEST

/* A save that fails says which temporary file it was, and leaves none. */
START_TEST(failed_save_names_its_temporary)
{
  char p[200], err[600];
  struct iovec v = {"text", 4};
  snprintf(p, sizeof p, "%s/no/such/c.kp.state", dir);
  ck_assert_int_eq(atomic_write(p, "c.kp.state", 0644, &v, 1, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "c.kp.state: cannot create the temporary file ") &&
                  strstr(err, "/no/such/c.kp.state.tmp") &&
                  strstr(err, " beside it: No such file or directory"),
                "%s", err);
  /* the rename fails: a directory of that name with a file in it */
  snprintf(p, sizeof p, "%s/full", dir);
  ck_assert_int_eq(mkdir(p, 0700), 0);
  snprintf(p, sizeof p, "%s/full/x", dir);
  write_file(p, "x");
  snprintf(p, sizeof p, "%s/full", dir);
  ck_assert_int_eq(atomic_write(p, "full", 0644, &v, 1, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "full: cannot rename the temporary file ") && strstr(err, "/full.tmp") &&
                  strstr(err, " over it: "),
                "%s", err);
  snprintf(p, sizeof p, "ls '%s' | grep -q '^full\\.tmp'", dir);
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

/* A file of `size` bytes of a repeating pattern at p. */
static void write_pattern(const char *p, size_t size)
{
  FILE *f = fopen(p, "wb");
  ck_assert_ptr_nonnull(f);
  for (size_t i = 0; i < size; i++)
    fputc("G01 X+1 ^\n"[i % 10], f);
  ck_assert_int_eq(fclose(f), 0);
}

START_TEST(load_maps_large_files)
{
  char p[160], err[400], *b, *r;
  size_t n, rn;
  long pg = sysconf(_SC_PAGESIZE);
  /* below FILE_MAP_MIN: read (free() would do); from it on: mapped, and
   * NUL-terminated even at a page boundary */
  size_t sizes[] = {FILE_MAP_MIN - 1, FILE_MAP_MIN, FILE_MAP_MIN + 123, 2 * FILE_MAP_MIN};
  for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) {
    snprintf(p, sizeof p, "%s/big%zu", dir, k);
    write_pattern(p, sizes[k]);
    ck_assert_msg(file_load(p, FILE_REGULAR, FILE_MAX_PROGRAM, &b, &n, err, sizeof err) == 0, "%s", err);
    ck_assert_msg(file_read_all(p, FILE_REGULAR, FILE_MAX_PROGRAM, &r, &rn, err, sizeof err) == 0, "%s", err);
    ck_assert_uint_eq(n, sizes[k]);
    ck_assert_uint_eq(rn, n);
    ck_assert_int_eq(memcmp(b, r, n + 1), 0);   /* the NUL as well */
    ck_assert_int_eq(b[n], 0);
    ck_assert_int_eq(file_cut(b), 0);
    free(r);
    file_unload(b);
  }
  ck_assert_int_eq(sizes[3] % (size_t)pg, 0);
  /* the limit still holds for a mapped file */
  ck_assert_int_eq(file_load(p, FILE_REGULAR, FILE_MAP_MIN, &b, &n, err, sizeof err), -2);
  ck_assert_msg(strstr(err, "too large"), "%s", err);
  /* more mapped at once than there are slots: the rest are read */
  char *m[6];
  for (int i = 0; i < 6; i++) {
    ck_assert_msg(file_load(p, FILE_REGULAR, FILE_MAX_PROGRAM, &m[i], &n, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(m[i][n - 1], "G01 X+1 ^\n"[(n - 1) % 10]);
  }
  for (int i = 0; i < 6; i++)
    file_unload(m[i]);
  file_unload(NULL);
}
END_TEST

START_TEST(load_survives_a_cut_file)
{
  /* a file cut short while mapped: no SIGBUS, zeros past the new end, and
   * file_cut says so */
  char p[160], err[400], *b;
  size_t n;
  long pg = sysconf(_SC_PAGESIZE);
  snprintf(p, sizeof p, "%s/cut", dir);
  write_pattern(p, 3 * FILE_MAP_MIN);
  ck_assert_msg(file_load(p, FILE_REGULAR, FILE_MAX_PROGRAM, &b, &n, err, sizeof err) == 0, "%s", err);
  ck_assert_int_eq(b[0], 'G');
  ck_assert_int_eq(truncate(p, 100), 0);
  ck_assert_int_eq(b[53], ' ');   /* still the file */
  ck_assert_int_eq(file_cut(b), 0);
  size_t zeros = 0;
  for (size_t i = (size_t)pg; i < n; i += 4096)
    zeros += b[i] == 0;
  ck_assert_uint_eq(zeros, (n - (size_t)pg + 4095) / 4096);
  ck_assert_int_eq(b[n], 0);
  ck_assert_int_eq(file_cut(b), 1);
  file_unload(b);
  ck_assert_int_eq(file_cut(p), 0);   /* not a mapping */
}
END_TEST

START_TEST(load_foreign_sigbus_still_kills)
{
  char p[160], err[400], *b;
  size_t n;
  snprintf(p, sizeof p, "%s/big", dir);
  write_pattern(p, FILE_MAP_MIN);
  signal(SIGBUS, SIG_DFL);   /* the disposition before (a sanitizer's own handler would abort instead) */
  ck_assert_msg(file_load(p, FILE_REGULAR, FILE_MAX_PROGRAM, &b, &n, err, sizeof err) == 0, "%s", err);
  raise(SIGBUS);   /* Check expects this test to die of it */
}
END_TEST

Suite *suite_state(void)
{
  Suite *s_ = suite_create("state");
  TCase *tc = tcase_create("restore");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, saved_and_restored);
  tcase_add_test(tc, unedited_copy_accepted);
  tcase_add_loop_test(tc, edited_field_refused, 0, (int)(sizeof edits / sizeof *edits));
  tcase_add_test(tc, random_edits_refused_or_safe);
  tcase_set_timeout(tc, 60);
  suite_add_tcase(s_, tc);
  tc = tcase_create("files");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, save_never_replaces_a_non_state);
  tcase_add_test(tc, stale_temporary_removed);
  tcase_add_test(tc, concurrent_saves_keep_their_temporaries);
  tcase_add_test(tc, failed_save_names_its_temporary);
  tcase_add_test(tc, read_refuses_fifo_and_devices);
  tcase_add_test(tc, read_sizes);
  tcase_add_test(tc, read_stdin_pipe);
  tcase_add_test(tc, load_maps_large_files);
  tcase_add_test(tc, load_survives_a_cut_file);
  tcase_add_test_raise_signal(tc, load_foreign_sigbus_still_kills, SIGBUS);
  suite_add_tcase(s_, tc);
  return s_;
}
