#pragma once
// The operations of the expression language and their value on numbers: the one definition that
// constant folding (expression.cpp) and the interpreter (interpreter.hpp, host and device) share.
#include <cmath>
#include <cstdint>

#include "core/hd.hpp"

namespace structmd::expression {

enum class Op : uint8_t {
    constant, input, column,
    add, sub, mul, div, neg, pow, powi,  // powi: an integer exponent (Node::index)
    sqrt, exp, log, sin, cos, tan, acos, asin, atan, tanh, cosh, sinh, abs,
    min, max, step, select,
    output  // bytecode only (interpreter.hpp): copies a register to an output
};

// Operand count of an operation (0 for leaves).
SMD_HD constexpr int arity(Op op) {
    return op == Op::constant || op == Op::input || op == Op::column ? 0
           : op == Op::select                                        ? 3
           : op == Op::add || op == Op::sub || op == Op::mul || op == Op::div || op == Op::pow || op == Op::min ||
                   op == Op::max
               ? 2
               : 1;
}

// x^n by repeated squaring (n may be negative).
template <class R>
SMD_HD SMD_INLINE R integer_power(R x, int n) {
    unsigned m = n < 0 ? unsigned(-n) : unsigned(n);
    R result = R(1);
    R base = x;
    while (m) {
        if (m & 1u) result *= base;
        base *= base;
        m >>= 1;
    }
    return n < 0 ? R(1) / result : result;
}

// The value of an operation of one to three operands. step(x) is 1 for x >= 0 and 0 below;
// select(c, a, b) is a where c != 0 and b elsewhere.
template <class R>
SMD_HD SMD_INLINE R apply(Op op, R a, R b, R c, int exponent) {
    using std::acos; using std::asin; using std::atan; using std::cos; using std::cosh; using std::exp;
    using std::fabs; using std::log; using std::pow; using std::sin; using std::sinh; using std::sqrt;
    using std::tan; using std::tanh;
    switch (op) {
        case Op::add: return a + b;
        case Op::sub: return a - b;
        case Op::mul: return a * b;
        case Op::div: return a / b;
        case Op::neg: return -a;
        case Op::pow: return pow(a, b);
        case Op::powi: return integer_power(a, exponent);
        case Op::sqrt: return sqrt(a);
        case Op::exp: return exp(a);
        case Op::log: return log(a);
        case Op::sin: return sin(a);
        case Op::cos: return cos(a);
        case Op::tan: return tan(a);
        case Op::acos: return acos(a);
        case Op::asin: return asin(a);
        case Op::atan: return atan(a);
        case Op::tanh: return tanh(a);
        case Op::cosh: return cosh(a);
        case Op::sinh: return sinh(a);
        case Op::abs: return fabs(a);
        case Op::min: return a < b ? a : b;
        case Op::max: return a > b ? a : b;
        case Op::step: return a >= R(0) ? R(1) : R(0);
        case Op::select: return a != R(0) ? b : c;
        default: return R(0);
    }
}

}  // namespace structmd::expression
