#pragma once
// The Expression components on a backend that compiles kernels at run time (CUDA): the energy and
// its derivatives become C++ source (expression/source_emitter.hpp), a Function of
// expression_terms.hpp compiled once at load into the kernels of the built-in terms
// (compiled_interaction.hpp). Its Params are the values of the data columns, nothing else: the
// program the interpreter would run is the compiled code itself.
#include <string>
#include <vector>

#include "core/logger.hpp"
#include "expression/source_emitter.hpp"
#include "forcefield/compiled_interaction.hpp"

namespace structmd {

// Reals in the Params of the compiled Function of an expression with `columns` data columns.
inline size_t compiled_expression_width(size_t columns) { return columns > 0 ? columns : 1; }  // no array of size 0

// The source of RuntimeExpression, the Function computing `roots` of `graph` (energy, then its
// derivatives) from `inputs` inputs and `columns` data columns, and of RuntimePotential, the term
// `potential` of expression_terms.hpp over it (such as "ExpressionBond<3, RuntimeExpression>").
inline RuntimeSource compiled_expression_source(const expression::Expression& graph, const std::vector<int>& roots,
                                                size_t inputs, size_t columns, const std::string& potential) {
    expression::SourceNames names;
    names.real = "R";
    for (size_t k = 0; k < inputs; ++k) names.inputs.push_back("inputs[" + std::to_string(k) + "]");
    for (size_t k = 0; k < columns; ++k) names.columns.push_back("p.columns[" + std::to_string(k) + "]");
    std::vector<std::string> outputs;
    for (size_t k = 0; k < roots.size(); ++k) outputs.push_back("outputs[" + std::to_string(k) + "]");
    RuntimeSource source;
    source.definition =
        "#include \"forcefield/expression_terms.hpp\"\n"
        "struct RuntimeExpression {\n"
        "    template <class R> struct Params { R columns[" + std::to_string(compiled_expression_width(columns)) + "]; };\n"
        "    template <class R> static SMD_HD SMD_INLINE void evaluate(const R* inputs, const Params<R>& p, R* outputs) {\n" +
        expression::emit_source(graph, roots, outputs, names) +
        "    }\n"
        "};\n"
        "using RuntimePotential = " + potential + ";\n";
    return source;
}

// Appends the columns of a type pair or bond in the compiled Params' layout.
template <class R>
void append_columns(std::vector<R>& flat, const R* columns, size_t count) {
    for (size_t k = 0; k < compiled_expression_width(count); ++k) flat.push_back(k < count ? columns[k] : R(0));
}

inline void log_compile_time(const Logger* log, const std::string& path, double seconds) {
    if (log) log->info(path + ": compiled for the GPU in " + std::to_string(seconds) + " s");
}

}  // namespace structmd
