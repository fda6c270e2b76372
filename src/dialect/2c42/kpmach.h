/* The 2С42 block on the grinder: what one block of the language means to
 * the machine (its motion, plane, G and M words, word values), turned into
 * the machine's canonical calls -- the wheel, the switches, a line, an arc,
 * a dwell, Y's return -- with the 2С42's own messages. */
#ifndef S42_KPMACH_H
#define S42_KPMACH_H

#include "machine.h"
#include <stddef.h>
#include <stdint.h>

struct kp_block {
  int motion;          /* enum motion (kp.h) */
  int plane;           /* 0, 17, 18, 19 */
  uint64_t g;
  uint32_t m;
  uint16_t given;      /* word slots given (ast.h SL_*) */
  double w[16];        /* their values, rounded as the language says */
  double f;            /* contour speed in force for this block */
  double d1;
};

/* The plane of G17 G18 G19 (enum geom_plane). */
int kp_plane(int g);
/* The block's contour path (G01, G02, G03; the arcs G12 G13 too, for their
 * travel) from the position pos (discretes): 1 with it in *pa, 0 when the
 * block has none. */
int kp_path(const int64_t pos[4], const struct kp_block *b, struct mach_path *pa);
/* Check the block against the machine's state; nothing changes.  0, or an
 * error code (vm/errors.h) with the message in msg. */
int kp_mach_check(const struct machine *m, const struct kp_block *b, char *msg, size_t n);
/* Carry the block out (it passed the check), in two steps: the modal
 * changes (the wheel first, M22/M23, M25/M26), then the core's motion or
 * dwell (G01 G02 G03 G04 G37). */
void kp_mach_modal(struct machine *m, const struct kp_block *b);
/* 0, or the machine's error code with msg (none after a passed check). */
int kp_mach_motion(struct machine *m, const struct kp_block *b, struct mach_out *o, char *msg, size_t n);
/* A plugin's contour move (the host's move()): increments d, the length
 * and speed limit it computed; along: the arc it follows (a helix), NULL a
 * line.  0, or the machine's error code with msg. */
int kp_mach_path_move(struct machine *m, const struct mach_path *along, const double d[4], double len,
                      double limit, double f, struct mach_out *o, char *msg, size_t n);
/* Arc of a G02/G03 block: length in mm, the largest Y share of the tangent
 * along it (0..1).  Returns 0, or E-ARC with a message. */
int kp_mach_arc(const struct kp_block *b, double *len_mm, double *yshare, char *msg, size_t n);
/* Does the block's core contour move an axis (a 0 % override holds it)? */
int kp_mach_moves(const struct kp_block *b);

#endif
