#pragma once
// Compiles expression nodes (expression.hpp) into one register program (interpreter.hpp) that
// computes them all: every node reachable from the roots is evaluated once, in an order where its
// operands come first, into the lowest free register; a register is freed after the last
// instruction that reads it. Constants were folded when the graph was built.
#include <string>
#include <vector>

#include "expression/expression.hpp"
#include "expression/interpreter.hpp"

namespace structmd::expression {

struct Program {
    std::vector<Instruction> code;
    std::vector<double> constants;
    int registers = 0;  // the most registers live at once
    int outputs = 0;

    // Runs the program on the host in double (for checks at load: a value at the cut-off).
    std::vector<double> run(const std::vector<double>& inputs, const std::vector<double>& columns) const;
};

// outputs[k] of the program is the value of roots[k]. Throws ExpressionError (column 0) when the
// expression needs more than kMaxRegisters live values or kMaxConstants constants.
Program compile(const Expression& e, const std::vector<int>& roots);

}  // namespace structmd::expression
