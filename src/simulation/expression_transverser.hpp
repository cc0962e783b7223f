#pragma once
// An expression transverser as the engine is asked to run it (SimulationProbes::expression_sum): the
// expression of a pair, parsed and compiled (src/expression/), the traversal (a neighbour list of a
// cutoff, or all pairs) and the group. Backend-free: the engine uploads or compiles it
// (engine_transversers.hpp); the step and the C API make it from their own input.
#include <string>
#include <vector>

#include "expression/compiler.hpp"
#include "expression/expression.hpp"

namespace structmd {

struct ExpressionTransverserSpec {
    std::string text;  // the expression, as given
    std::string path;  // where it was given, for messages ("simulationStep.coordination.parameters.compute")
    double cutoff = 0;  // > 0: pairs closer than this over a neighbour list; 0: all pairs
    int group = -1;     // the force field's group whose particles take part (both of a pair); -1: all
    expression::Expression graph;
    int root = -1;
    expression::Program program;  // computes the root

    // Two specs with the same key run the same traversal (the engine prepares it once).
    std::string key() const;
};

// The names the expression may use, in the order of their input slots (ExpressionSumInput).
const std::vector<std::string>& expression_transverser_inputs();

// The source of the expression's traversal kernels for a backend that compiles at run time (NVRTC):
// `names` are the kernel over a neighbour list, then the two over all pairs (split among lanes, and in
// shared-memory tiles: all_pairs_traversal.hpp), in the real type `real` ("float" or "double"), each
// launched with the functor of prepared_expression_sum.hpp.
struct ExpressionSumKernels {
    std::string source;
    std::vector<std::string> names;
};
ExpressionSumKernels expression_sum_kernels(const ExpressionTransverserSpec& spec, const std::string& real);

// Parses and compiles `text`. An unknown name, a syntax error or a negative or non-finite cutoff is
// ERR_INPUT at `path`.
ExpressionTransverserSpec make_expression_transverser(const std::string& text, const std::string& path,
                                                      double cutoff, int group);

}  // namespace structmd
