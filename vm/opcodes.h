/* The one opcode table.  Every instruction is a 32-bit word: the opcode in
 * the low 8 bits, one operand A in the high 24.  The enum, the names, the
 * operand kinds, the stack effects, the disassembler and docs/opcodes.md are
 * all generated from this list; there is no second list kept by hand.
 *
 * OP(name, operand kind, pop, push, "meaning")
 * Operand kinds: NONE; K constant index; I small integer; REG register;
 * SLOT word slot; SET destination+rule (dest | rule<<10); ARR array access
 * (arr | mode<<2, arr below the program's lim.arrays); MASK array mask (bit n
 * array n, within lim.arrays); REL relation mask (1 <, 2 =, 4 >); PC jump
 * target; BLK block index.  The limits named lim.* are the program's
 * (vm/program.h), the messages its table's (vm/msgs.h). */
#ifndef S42_OPCODES_H
#define S42_OPCODES_H

#define S42_OPCODES(OP) \
  OP(BLOCK,  BLK,  0, 0, "start block A: count it against the budget, open its transaction") \
  OP(CONST,  K,    0, 1, "push constant K[A]") \
  OP(INT,    I,    0, 1, "push the integer A") \
  OP(REG,    REG,  0, 1, "push register A") \
  OP(WORD,   SLOT, 0, 1, "push the value of word slot A given earlier in this block") \
  OP(NEG,    NONE, 1, 1, "negate") \
  OP(ADD,    NONE, 2, 1, "add") \
  OP(SUB,    NONE, 2, 1, "subtract") \
  OP(MUL,    NONE, 2, 1, "multiply") \
  OP(DIV,    NONE, 2, 1, "divide (E-DIV0 on zero)") \
  OP(POW,    NONE, 2, 1, "power (E-DOMAIN for a negative base with a fractional exponent)") \
  OP(SIN,    NONE, 1, 1, "sine of x in the program's angle unit (E-DOMAIN for |x| over lim.trig_max)") \
  OP(COS,    NONE, 1, 1, "cosine of x in the angle unit (|x| <= lim.trig_max)") \
  OP(TAN,    NONE, 1, 1, "tangent of x in the angle unit (|x| <= lim.trig_max, not at odd multiples of 90 degrees)") \
  OP(ASIN,   NONE, 1, 1, "arcsine in the angle unit (|x| <= 1)") \
  OP(ACOS,   NONE, 1, 1, "arccosine in the angle unit (|x| <= 1)") \
  OP(ATAN,   NONE, 1, 1, "arctangent in the angle unit (|x| <= lim.atan_max)") \
  OP(LOG,    NONE, 1, 1, "natural logarithm (0 < x <= lim.log_max)") \
  OP(SET,    SET,  1, 0, "pop into register or word slot, converted and checked by rule") \
  OP(ARD,    ARR,  0, 1, "array read at the pointer (mode 1 then advance, 2 stay, 3 back first; E-ARRAY+ past lim.cells)") \
  OP(AWR,    ARR,  1, 0, "array write at the pointer (modes as ARD; E-RANGE outside lim.cell_lo..cell_hi)") \
  OP(AZERO,  MASK, 0, 0, "zero the arrays in A: cells, pointer and length") \
  OP(APTR0,  MASK, 0, 0, "pointer of the arrays in A to 0") \
  OP(APTREND,MASK, 0, 0, "pointer of the array in A to its length") \
  OP(CMP,    REL,  2, 1, "1 if the relation A holds between the two values, else 0") \
  OP(AND,    NONE, 2, 1, "logical and of two truth values") \
  OP(OR,     NONE, 2, 1, "logical or of two truth values") \
  OP(COND,   NONE, 1, 0, "pop the block's jump condition") \
  OP(MACH,   NONE, 0, 0, "yield the block to the host (machine work)") \
  OP(SYNC,   NONE, 0, 0, "yield the block to the host only when it watches every block") \
  OP(TRUNC,  REG,  0, 0, "register A to its integer part, towards zero") \
  OP(COMMIT, NONE, 0, 0, "close the block's transaction, count it executed") \
  OP(CALL,   PC,   1, 0, "call the sub at A, popped-count times (0: not at all; E-NEST past lim.depth)") \
  OP(PPJ,    PC,   0, 0, "operational jump to A if cycle exit is latched (clears it)") \
  OP(JMP,    PC,   0, 0, "jump to A") \
  OP(JCOND,  PC,   0, 0, "jump to A if the block's condition held") \
  OP(RET,    NONE, 0, 0, "end of sub: run it again or return to the caller (E-SUB in the main program)") \
  OP(END,    NONE, 0, 0, "end of program") \
  OP(RETEND, NONE, 0, 0, "RET in a called sub, END in the main program (Bosch M2, FMS-3000 M99)") \
  /* superinstructions: the common shapes of a block in one dispatch */ \
  OP(ADDI,   I,    1, 1, "add the integer A (INT A; ADD)") \
  OP(SUBI,   I,    1, 1, "subtract the integer A (INT A; SUB)") \
  OP(MULI,   I,    1, 1, "multiply by the integer A (INT A; MUL)") \
  OP(DIVI,   I,    1, 1, "divide by the integer A (INT A; DIV)") \
  OP(ADDK,   K,    1, 1, "add constant K[A] (CONST A; ADD)") \
  OP(SUBK,   K,    1, 1, "subtract constant K[A] (CONST A; SUB)") \
  OP(MULK,   K,    1, 1, "multiply by constant K[A] (CONST A; MUL)") \
  OP(DIVK,   K,    1, 1, "divide by constant K[A] (CONST A; DIV)") \
  OP(ADDR,   REG,  1, 1, "add register A (REG A; ADD)") \
  OP(SUBR,   REG,  1, 1, "subtract register A (REG A; SUB)") \
  OP(MULR,   REG,  1, 1, "multiply by register A (REG A; MUL)") \
  OP(DIVR,   REG,  1, 1, "divide by register A (REG A; DIV)") \
  OP(SETP,   REG,  1, 0, "pop into parameter register A, E-RANGE outside lim.param_lo..param_hi (SET with a parameter's rule)") \
  OP(CMPC,   REL,  2, 0, "the block's jump condition is the relation A between two values (CMP A; COND)") \
  OP(CMPCK,  RELK, 1, 0, "the block's jump condition is the relation A&7 between a value and constant K[A>>3] (CONST; CMPC)") \
  OP(CMPCR,  RELR, 1, 0, "the block's jump condition is the relation A&7 between a value and register A>>3 (REG; CMPC)") \
  OP(CJMP,   PC,   0, 0, "close the block's transaction, then jump to A (COMMIT; JMP)") \
  OP(CJCOND, PC,   0, 0, "close the block's transaction, then jump to A if the block's condition held (COMMIT; JCOND)")

enum vm_opd { OPD_NONE, OPD_K, OPD_I, OPD_REG, OPD_SLOT, OPD_SET, OPD_ARR,
              OPD_MASK, OPD_REL, OPD_RELK, OPD_RELR, OPD_PC, OPD_BLK };

enum vm_op {
#define OP_ENUM(name, opd, pop, push, doc) OP_##name,
  S42_OPCODES(OP_ENUM)
#undef OP_ENUM
  OP__COUNT
};
_Static_assert(OP__COUNT <= 256, "opcodes must fit in 8 bits");

#define INS(op, a) ((uint32_t)(op) | ((uint32_t)(a) << 8))
#define INS_OP(i) ((i) & 0xffu)
#define INS_A(i) ((i) >> 8)
#define INS_AMAX 0xffffffu

struct vm_opinfo { const char *name; int opd, pop, push; const char *doc; };
extern const struct vm_opinfo vm_ops[OP__COUNT];

#endif
