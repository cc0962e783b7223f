#pragma once
// The Expression terms (expression_terms.hpp) run by the bytecode interpreter (src/expression/),
// on the host and in CUDA kernels alike, in the precision of the term (PairR for pairs, R
// otherwise). Each Params points to its program in backend memory, which the interactor owns, and
// holds the values of its data columns (per type pair or per bond).
#include "expression/interpreter.hpp"
#include "forcefield/expression_terms.hpp"

namespace structmd {

struct InterpretedExpression {
    template <class R>
    struct Params {
        expression::ProgramView<R> program;
        R columns[expression::kMaxColumns];
    };

    template <class R>
    static SMD_HD SMD_INLINE void evaluate(const R* inputs, const Params<R>& p, R* outputs) {
        expression::run_program(p.program, inputs, p.columns, outputs);
    }
};

using InterpretedPair = ExpressionPair<InterpretedExpression>;
template <int N>
using InterpretedBond = ExpressionBond<N, InterpretedExpression>;
using InterpretedExternal = ExpressionExternal<InterpretedExpression>;

}  // namespace structmd
