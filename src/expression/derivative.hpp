#pragma once
// Symbolic differentiation of an expression (expression.hpp) with respect to one input slot. The
// derivative is built in the same graph, so it shares every node it has in common with the value
// (for sin(k r), the derivative k cos(k r) reuses k r), and the graph's simplifications apply to
// every new node. Rules at the points where a function has a kink or a jump: d/dx step(x) = 0,
// d/dx abs(x) = select(step(x), 1, -1), min and max take the derivative of the operand they return
// (the first where both are equal), select(c, a, b) differentiates the branch it takes.
#include "expression/expression.hpp"

namespace structmd::expression {

int differentiate(Expression& e, int root, int inputSlot);

}  // namespace structmd::expression
