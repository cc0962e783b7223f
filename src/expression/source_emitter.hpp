#pragma once
// An expression as C++ source, for a runtime-compiled (NVRTC) kernel: a block of statements that
// computes each root once from named variables, sharing common subexpressions as the bytecode does.
//
//   emit_source(e, {energy, dudr}, {"energy", "dudx"}, {"double", {"r"}, {"p.columns[0]"}})
// gives
//   {
//   const double t0 = r;
//   const double t1 = p.columns[0];
//   const double t2 = t1 / t0;
//   ...
//   energy = t7;
//   dudx = t9;
//   }
// The outputs must be declared (and assignable) where the block is pasted. The functions used are
// those of <cmath> (sqrt, exp, ..., pow, fabs), which CUDA's device library also provides; step,
// select, min and max become conditional expressions.
#include <string>
#include <vector>

#include "expression/expression.hpp"

namespace structmd::expression {

struct SourceNames {
    std::string real = "double";        // the type of every temporary ("float" or "double")
    std::vector<std::string> inputs;    // C++ expression of each input slot
    std::vector<std::string> columns;   // and of each data column
    std::string prefix = "t";           // of the temporaries' names
};

// outputs[k] names the variable assigned the value of roots[k].
std::string emit_source(const Expression& e, const std::vector<int>& roots, const std::vector<std::string>& outputs,
                        const SourceNames& names);

}  // namespace structmd::expression
