/* The one opcode table.  Every instruction is a 32-bit word: the opcode in
 * the low 8 bits, one operand A in the high 24.  The enum, the names, the
 * operand kinds, the stack effects, the disassembler and docs/opcodes.md are
 * all generated from this list; there is no second list kept by hand.
 *
 * OP(name, operand kind, extension word's operand kind, pop, push, "meaning")
 * Operand kinds: NONE; K constant index; I small integer; REG register;
 * SLOT word slot; SET destination+rule (dest | rule<<10); ARR array access
 * (arr | mode<<2, arr below the program's lim.arrays); MASK array mask (bit n
 * array n, within lim.arrays); REL relation mask (1 <, 2 =, 4 >); PC jump
 * target; BLK block index; RI, RK, RR register A&127 and A>>7 an integer, a
 * constant index or a register; KT a constant K[A] with its tolerance bounds
 * K[A+1], K[A+2] (vm_rel_bounds); SW a switch test, mask A&0xfff and the
 * state A>>12 the block sets (bits within the mask).  An extension operand kind other than NONE
 * makes the instruction two words: the second is EXT, its A that operand.  The limits named lim.* are the program's
 * (vm/program.h), the messages its table's (vm/msgs.h). */
#ifndef S42_OPCODES_H
#define S42_OPCODES_H

#define S42_OPCODES(OP) \
  OP(BLOCK,  BLK,  NONE, 0, 0, "start block A: count it against the budget, open its transaction") \
  OP(CONST,  K,    NONE, 0, 1, "push constant K[A]") \
  OP(INT,    I,    NONE, 0, 1, "push the integer A") \
  OP(REG,    REG,  NONE, 0, 1, "push register A") \
  OP(WORD,   SLOT, NONE, 0, 1, "push the value of word slot A given earlier in this block") \
  OP(NEG,    NONE, NONE, 1, 1, "negate") \
  OP(ADD,    NONE, NONE, 2, 1, "add") \
  OP(SUB,    NONE, NONE, 2, 1, "subtract") \
  OP(MUL,    NONE, NONE, 2, 1, "multiply") \
  OP(DIV,    NONE, NONE, 2, 1, "divide (E-DIV0 on zero)") \
  OP(POW,    NONE, NONE, 2, 1, "power (E-DOMAIN for a negative base with a fractional exponent)") \
  OP(SIN,    NONE, NONE, 1, 1, "sine of x in the program's angle unit (E-DOMAIN for |x| over lim.trig_max)") \
  OP(COS,    NONE, NONE, 1, 1, "cosine of x in the angle unit (|x| <= lim.trig_max)") \
  OP(TAN,    NONE, NONE, 1, 1, "tangent of x in the angle unit (|x| <= lim.trig_max, not at odd multiples of 90 degrees)") \
  OP(ASIN,   NONE, NONE, 1, 1, "arcsine in the angle unit (|x| <= 1)") \
  OP(ACOS,   NONE, NONE, 1, 1, "arccosine in the angle unit (|x| <= 1)") \
  OP(ATAN,   NONE, NONE, 1, 1, "arctangent in the angle unit (|x| <= lim.atan_max)") \
  OP(LOG,    NONE, NONE, 1, 1, "natural logarithm (0 < x <= lim.log_max)") \
  OP(SET,    SET,  NONE, 1, 0, "pop into register or word slot, converted and checked by rule") \
  OP(ARD,    ARR,  NONE, 0, 1, "array read at the pointer (mode 1 then advance, 2 stay, 3 back first; E-ARRAY+ past lim.cells)") \
  OP(AWR,    ARR,  NONE, 1, 0, "array write at the pointer (modes as ARD; E-RANGE outside lim.cell_lo..cell_hi)") \
  OP(AZERO,  MASK, NONE, 0, 0, "zero the arrays in A: cells, pointer and length") \
  OP(APTR0,  MASK, NONE, 0, 0, "pointer of the arrays in A to 0") \
  OP(APTREND,MASK, NONE, 0, 0, "pointer of the array in A to its length") \
  OP(CMP,    REL,  NONE, 2, 1, "1 if the relation A holds between the two values, else 0") \
  OP(AND,    NONE, NONE, 2, 1, "logical and of two truth values") \
  OP(OR,     NONE, NONE, 2, 1, "logical or of two truth values") \
  OP(COND,   NONE, NONE, 1, 0, "pop the block's jump condition") \
  OP(MACH,   NONE, NONE, 0, 0, "yield the block to the host (machine work)") \
  OP(SYNC,   NONE, NONE, 0, 0, "yield the block to the host only when it watches every block") \
  OP(TRUNC,  REG,  NONE, 0, 0, "register A to its integer part, towards zero") \
  OP(COMMIT, NONE, NONE, 0, 0, "close the block's transaction, count it executed") \
  OP(CALL,   PC,   NONE, 1, 0, "call the sub that starts at block A, popped-count times (0: not at all; E-NEST past lim.depth)") \
  OP(PPJ,    PC,   NONE, 0, 0, "operational jump to block A if cycle exit is latched (clears it)") \
  OP(JMP,    PC,   NONE, 0, 0, "jump to block A") \
  OP(JCOND,  PC,   NONE, 0, 0, "jump to block A if the block's condition held") \
  OP(RET,    NONE, NONE, 0, 0, "end of sub: run it again or return to the caller (E-SUB in the main program)") \
  OP(END,    NONE, NONE, 0, 0, "end of program") \
  OP(RETEND, NONE, NONE, 0, 0, "RET in a called sub, END in the main program (Bosch M2, FMS-3000 M99)") \
  /* superinstructions: the common shapes of a block in one dispatch */ \
  OP(ADDI,   I,    NONE, 1, 1, "add the integer A (INT A; ADD)") \
  OP(SUBI,   I,    NONE, 1, 1, "subtract the integer A (INT A; SUB)") \
  OP(MULI,   I,    NONE, 1, 1, "multiply by the integer A (INT A; MUL)") \
  OP(DIVI,   I,    NONE, 1, 1, "divide by the integer A (INT A; DIV)") \
  OP(ADDK,   K,    NONE, 1, 1, "add constant K[A] (CONST A; ADD)") \
  OP(SUBK,   K,    NONE, 1, 1, "subtract constant K[A] (CONST A; SUB)") \
  OP(MULK,   K,    NONE, 1, 1, "multiply by constant K[A] (CONST A; MUL)") \
  OP(DIVK,   K,    NONE, 1, 1, "divide by constant K[A] (CONST A; DIV)") \
  OP(ADDR,   REG,  NONE, 1, 1, "add register A (REG A; ADD)") \
  OP(SUBR,   REG,  NONE, 1, 1, "subtract register A (REG A; SUB)") \
  OP(MULR,   REG,  NONE, 1, 1, "multiply by register A (REG A; MUL)") \
  OP(DIVR,   REG,  NONE, 1, 1, "divide by register A (REG A; DIV)") \
  OP(SETP,   REG,  NONE, 1, 0, "pop into parameter register A, E-RANGE outside lim.param_lo..param_hi (SET with a parameter's rule)") \
  OP(CMPC,   REL,  NONE, 2, 0, "the block's jump condition is the relation A between two values (CMP A; COND)") \
  OP(CMPCK,  RELK, NONE, 1, 0, "the block's jump condition is the relation A&7 between a value and constant K[A>>3] (CONST; CMPC)") \
  OP(CMPCR,  RELR, NONE, 1, 0, "the block's jump condition is the relation A&7 between a value and register A>>3 (REG; CMPC)") \
  OP(CJMP,   PC,   NONE, 0, 0, "close the block's transaction, then jump to block A (COMMIT; JMP)") \
  OP(CJCOND, PC,   NONE, 0, 0, "close the block's transaction, then jump to block A if the block's condition held (COMMIT; JCOND)") \
  /* register forms, fused by the 2С42's peephole pass (src/dialect/2c42/peep.c); \
   * a two-word one is followed by an EXT word: its second operand, and in \
   * the column map the column of its SETP part */ \
  OP(EXT,    NONE, NONE, 0, 0, "extension word of the instruction before it (its second operand and the column of its last part); never runs") \
  OP(RADDI,  RI,   NONE, 0, 1, "push register A&127 plus the integer A>>7 (REG; ADDI)") \
  OP(RSUBI,  RI,   NONE, 0, 1, "push register A&127 minus the integer A>>7 (REG; SUBI)") \
  OP(RMULI,  RI,   NONE, 0, 1, "push register A&127 times the integer A>>7 (REG; MULI)") \
  OP(RDIVI,  RI,   NONE, 0, 1, "push register A&127 divided by the integer A>>7 (REG; DIVI)") \
  OP(RADDK,  RK,   NONE, 0, 1, "push register A&127 plus constant K[A>>7] (REG; ADDK)") \
  OP(RSUBK,  RK,   NONE, 0, 1, "push register A&127 minus constant K[A>>7] (REG; SUBK)") \
  OP(RMULK,  RK,   NONE, 0, 1, "push register A&127 times constant K[A>>7] (REG; MULK)") \
  OP(RDIVK,  RK,   NONE, 0, 1, "push register A&127 divided by constant K[A>>7] (REG; DIVK)") \
  OP(RADDR,  RR,   NONE, 0, 1, "push register A&127 plus register A>>7 (REG; ADDR)") \
  OP(RSUBR,  RR,   NONE, 0, 1, "push register A&127 minus register A>>7 (REG; SUBR)") \
  OP(RMULR,  RR,   NONE, 0, 1, "push register A&127 times register A>>7 (REG; MULR)") \
  OP(RDIVR,  RR,   NONE, 0, 1, "push register A&127 divided by register A>>7 (REG; DIVR)") \
  OP(ADDP,   NONE, REG,  2, 0, "add, into parameter register EXT (ADD; SETP)") \
  OP(SUBP,   NONE, REG,  2, 0, "subtract, into parameter register EXT (SUB; SETP)") \
  OP(MULP,   NONE, REG,  2, 0, "multiply, into parameter register EXT (MUL; SETP)") \
  OP(DIVP,   NONE, REG,  2, 0, "divide, into parameter register EXT (DIV; SETP)") \
  OP(ADDIP,  I,    REG,  1, 0, "add the integer A, into parameter register EXT (ADDI; SETP)") \
  OP(SUBIP,  I,    REG,  1, 0, "subtract the integer A, into parameter register EXT (SUBI; SETP)") \
  OP(MULIP,  I,    REG,  1, 0, "multiply by the integer A, into parameter register EXT (MULI; SETP)") \
  OP(DIVIP,  I,    REG,  1, 0, "divide by the integer A, into parameter register EXT (DIVI; SETP)") \
  OP(ADDKP,  K,    REG,  1, 0, "add constant K[A], into parameter register EXT (ADDK; SETP)") \
  OP(SUBKP,  K,    REG,  1, 0, "subtract constant K[A], into parameter register EXT (SUBK; SETP)") \
  OP(MULKP,  K,    REG,  1, 0, "multiply by constant K[A], into parameter register EXT (MULK; SETP)") \
  OP(DIVKP,  K,    REG,  1, 0, "divide by constant K[A], into parameter register EXT (DIVK; SETP)") \
  OP(ADDRP,  REG,  REG,  1, 0, "add register A, into parameter register EXT (ADDR; SETP)") \
  OP(SUBRP,  REG,  REG,  1, 0, "subtract register A, into parameter register EXT (SUBR; SETP)") \
  OP(MULRP,  REG,  REG,  1, 0, "multiply by register A, into parameter register EXT (MULR; SETP)") \
  OP(DIVRP,  REG,  REG,  1, 0, "divide by register A, into parameter register EXT (DIVR; SETP)") \
  OP(RADDIP, RI,   REG,  0, 0, "parameter register EXT = register A&127 plus the integer A>>7 (REG; ADDI; SETP)") \
  OP(RSUBIP, RI,   REG,  0, 0, "parameter register EXT = register A&127 minus the integer A>>7 (REG; SUBI; SETP)") \
  OP(RMULIP, RI,   REG,  0, 0, "parameter register EXT = register A&127 times the integer A>>7 (REG; MULI; SETP)") \
  OP(RDIVIP, RI,   REG,  0, 0, "parameter register EXT = register A&127 divided by the integer A>>7 (REG; DIVI; SETP)") \
  OP(RADDKP, RK,   REG,  0, 0, "parameter register EXT = register A&127 plus constant K[A>>7] (REG; ADDK; SETP)") \
  OP(RSUBKP, RK,   REG,  0, 0, "parameter register EXT = register A&127 minus constant K[A>>7] (REG; SUBK; SETP)") \
  OP(RMULKP, RK,   REG,  0, 0, "parameter register EXT = register A&127 times constant K[A>>7] (REG; MULK; SETP)") \
  OP(RDIVKP, RK,   REG,  0, 0, "parameter register EXT = register A&127 divided by constant K[A>>7] (REG; DIVK; SETP)") \
  OP(RADDRP, RR,   REG,  0, 0, "parameter register EXT = register A&127 plus register A>>7 (REG; ADDR; SETP)") \
  OP(RSUBRP, RR,   REG,  0, 0, "parameter register EXT = register A&127 minus register A>>7 (REG; SUBR; SETP)") \
  OP(RMULRP, RR,   REG,  0, 0, "parameter register EXT = register A&127 times register A>>7 (REG; MULR; SETP)") \
  OP(RDIVRP, RR,   REG,  0, 0, "parameter register EXT = register A&127 divided by register A>>7 (REG; DIVR; SETP)") \
  OP(SINP,   NONE, REG,  1, 0, "sine, into parameter register EXT (SIN; SETP)") \
  OP(COSP,   NONE, REG,  1, 0, "cosine, into parameter register EXT (COS; SETP)") \
  OP(ASINP,  NONE, REG,  1, 0, "arcsine, into parameter register EXT (ASIN; SETP)") \
  OP(ACOSP,  NONE, REG,  1, 0, "arccosine, into parameter register EXT (ACOS; SETP)") \
  OP(ATANP,  NONE, REG,  1, 0, "arctangent, into parameter register EXT (ATAN; SETP)") \
  OP(RSIN,   REG,  NONE, 0, 1, "push the sine of register A (REG; SIN)") \
  OP(RCOS,   REG,  NONE, 0, 1, "push the cosine of register A (REG; COS)") \
  OP(RSINCOS, REG, NONE, 0, 2, "push the sine, then the cosine, of register A, both from one sincos (REG; SIN; REG; COS)") \
  OP(RCOSSIN, REG, NONE, 0, 2, "push the cosine, then the sine, of register A, both from one sincos (REG; COS; REG; SIN)") \
  OP(CMPRK,  RELR, KT,   0, 0, "the block's jump condition is the relation A&7 between register A>>3 and constant K[EXT], K[EXT+1] and K[EXT+2] its bounds outside which the relation is plainly < or > (REG; CMPCK)") \
  /* a block's control in one dispatch (src/dialect/2c42/compile.c) */ \
  OP(CCALL,  PC,   NONE, 0, 0, "close the block's transaction, then call the sub at block A once (COMMIT; INT 1; CALL)") \
  OP(BLOCKR, BLK,  NONE, 0, 0, "BLOCK A of a block that is SYNC; COMMIT; RET and nothing else (a sub's lone M17): when the host watches neither it nor every block, all four at once") \
  OP(MACHS,  SW,   NONE, 0, 0, "MACH of a block that only sets the host's switches: runs on as SYNC when the host has published its switches (vm.sw has VM_SW_HELD) and those in mask A&0xfff already stand as A>>12 says")

enum vm_opd { OPD_NONE, OPD_K, OPD_I, OPD_REG, OPD_SLOT, OPD_SET, OPD_ARR,
              OPD_MASK, OPD_REL, OPD_RELK, OPD_RELR, OPD_PC, OPD_BLK,
              OPD_RI, OPD_RK, OPD_RR, OPD_KT, OPD_SW };

enum vm_op {
#define OP_ENUM(name, opd, ext, pop, push, doc) OP_##name,
  S42_OPCODES(OP_ENUM)
#undef OP_ENUM
  OP__COUNT
};
_Static_assert(OP__COUNT <= 256, "opcodes must fit in 8 bits");

#define INS(op, a) ((uint32_t)(op) | ((uint32_t)(a) << 8))
#define INS_OP(i) ((i) & 0xffu)
#define INS_A(i) ((i) >> 8)
#define INS_AMAX 0xffffffu

/* The opcodes that start a block (a block's first instruction). */
static inline int vm_op_starts_block(unsigned op)
{
  return op == OP_BLOCK || op == OP_BLOCKR;
}

/* ext: the operand kind of the EXT word that follows, OPD_NONE when the
 * instruction is one word (vm_op_len). */
struct vm_opinfo { const char *name; int opd, ext, pop, push; const char *doc; };
extern const struct vm_opinfo vm_ops[OP__COUNT];

/* Words of an instruction: 2 when an EXT word follows it. */
static inline int vm_op_len(unsigned op)
{
  return op < OP__COUNT && vm_ops[op].ext != OPD_NONE ? 2 : 1;
}

#endif
