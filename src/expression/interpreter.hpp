#pragma once
// The bytecode of a compiled expression and its interpreter, one source for the CPU backend and
// CUDA kernels, in float or double.
//
// A program is a list of register instructions, one operation each (one dispatch per instruction).
// Each writes one register (dst) from up to three registers (a, b, c), or loads a register from the
// constant table (Op::constant: constants[a]), an input (Op::input: inputs[a], r, theta, phi or
// x, y, z, t) or a data column (Op::column: columns[a], the values of the type pair, bond or entry);
// Op::output copies register a to outputs[dst]. Registers are reused once their value
// is dead, so a program needs at most kMaxRegisters of them, whatever its length.
#include <cstdint>

#include "core/hd.hpp"
#include "expression/operations.hpp"

namespace structmd::expression {

inline constexpr int kMaxRegisters = 32;
inline constexpr int kMaxConstants = 256;
inline constexpr int kMaxColumns = 8;  // data columns an expression may name

struct Instruction {
    Op op;
    uint8_t dst;  // a register; for Op::output, the output index
    uint8_t a, b, c;
    int8_t exponent;  // powi
    uint8_t unused[2];
};
static_assert(sizeof(Instruction) == 8, "an instruction is 8 bytes");

// A program in backend memory: its instructions and its constants, converted to R.
template <class R>
struct ProgramView {
    const Instruction* code = nullptr;
    const R* constants = nullptr;
    int length = 0;
};

// Runs a program: writes each of its outputs.
template <class R>
SMD_HD SMD_INLINE void run_program(const ProgramView<R>& program, const R* inputs, const R* columns, R* outputs) {
    R reg[kMaxRegisters];
    for (int pc = 0; pc < program.length; ++pc) {
        const Instruction in = program.code[pc];
        switch (in.op) {
            case Op::constant: reg[in.dst] = program.constants[in.a]; break;
            case Op::input: reg[in.dst] = inputs[in.a]; break;
            case Op::column: reg[in.dst] = columns[in.a]; break;
            case Op::output: outputs[in.dst] = reg[in.a]; break;
            default: reg[in.dst] = apply<R>(in.op, reg[in.a], reg[in.b], reg[in.c], in.exponent); break;
        }
    }
}

}  // namespace structmd::expression
