#pragma once
// ["NonBonded","Expression"] on a backend that compiles kernels at run time (CUDA): the energy and
// its derivative become C++ source (expression/source_emitter.hpp), compiled once at load into the
// pair traversal of the built-in potentials (compiled_pair_interaction.hpp). The parameters of a
// type pair are the interpreter's (expression_potentials.hpp) less the program pointer: cutoff2,
// offset, then the data columns.
#include <memory>
#include <string>
#include <vector>

#include "core/logger.hpp"
#include "expression/source_emitter.hpp"
#include "forcefield/compiled_pair_interaction.hpp"
#include "forcefield/expression_potentials.hpp"
#include "forcefield/interactor_build.hpp"

namespace structmd {

struct ExpressionConfig;

// The RuntimePotential of an expression of r with `columns` data columns.
inline RuntimePairPotential expression_pair_source(const expression::Expression& graph, const std::vector<int>& roots,
                                                   size_t columns) {
    expression::SourceNames names;
    names.real = "R";
    names.inputs = {"r"};
    for (size_t k = 0; k < columns; ++k) names.columns.push_back("p.columns[" + std::to_string(k) + "]");
    const size_t stored = columns > 0 ? columns : 1;  // no array of size 0
    RuntimePairPotential potential;
    potential.width = 2 + stored;
    potential.definition = "struct RuntimePotential {\n"
                           "    template <class R> struct Params { R cutoff2; R offset; R columns[" +
                           std::to_string(stored) +
                           "]; };\n"
                           "    template <class R> static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {\n"
                           "        const R r = sqrt(r2);\n"
                           "        R energy, dudr;\n" +
                           expression::emit_source(graph, roots, {"energy", "dudr"}, names) +
                           "        return {dudr / r, energy + p.offset};\n"
                           "    }\n"
                           "};\n";
    return potential;
}

template <class B, class R, class PairR>
std::unique_ptr<Interactor<B, R>> make_compiled_expression_pair(const InteractorBuild<B, R>& build,
                                                                const PairSpec& pair,
                                                                const expression::Expression& graph,
                                                                const std::vector<int>& roots, size_t columns,
                                                                const std::vector<ExpressionPair::Params<PairR>>& table) {
    const RuntimePairPotential potential = expression_pair_source(graph, roots, columns);
    std::vector<PairR> flat;
    flat.reserve(table.size() * potential.width);
    for (const auto& p : table) {
        flat.push_back(p.cutoff2);
        flat.push_back(p.offset);
        for (size_t k = 0; k < potential.width - 2; ++k) flat.push_back(k < columns ? p.columns[k] : PairR(0));
    }
    auto interactor = std::make_unique<CompiledPairInteraction<B, R, PairR>>(
        build.backend, build.scope(pair), build.listFor(pair), potential, flat, static_cast<int>(build.context.ntypes));
    if (build.context.log)
        build.context.log->info(pair.path + ": compiled for the GPU in " + std::to_string(interactor->compile_seconds()) +
                                " s");
    return interactor;
}

}  // namespace structmd
