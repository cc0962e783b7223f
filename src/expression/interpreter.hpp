#pragma once
// The bytecode of a compiled expression and its interpreter, one source for the CPU backend and
// CUDA kernels, in float or double.
//
// A program is a list of register instructions. Each writes one register (dst) from up to three
// registers (a, b, c), or loads a register from the constant table (constant[a]), an input
// (inputs[a]: r, theta, phi or x, y, z) or a data column (columns[a]: the values of the type pair,
// bond or entry); `output` copies register a to outputs[dst]. Registers are reused once their value
// is dead, so a program needs at most kMaxRegisters of them, whatever its length.
#include <cstdint>

#include "core/hd.hpp"
#include "expression/operations.hpp"

namespace structmd::expression {

inline constexpr int kMaxRegisters = 32;
inline constexpr int kMaxConstants = 256;
inline constexpr int kMaxColumns = 8;  // data columns an expression may name

enum class Code : uint8_t { constant, input, column, output, operation };

struct Instruction {
    Code code;
    Op op;        // for Code::operation
    uint8_t dst;  // a register; for Code::output, the output index
    uint8_t a, b, c;
    int8_t exponent;  // powi
    uint8_t unused = 0;
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
        switch (in.code) {
            case Code::constant: reg[in.dst] = program.constants[in.a]; break;
            case Code::input: reg[in.dst] = inputs[in.a]; break;
            case Code::column: reg[in.dst] = columns[in.a]; break;
            case Code::output: outputs[in.dst] = reg[in.a]; break;
            case Code::operation:
                reg[in.dst] = apply<R>(in.op, reg[in.a], reg[in.b], reg[in.c], in.exponent);
                break;
        }
    }
}

}  // namespace structmd::expression
