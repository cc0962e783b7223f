#pragma once
// The Expression components: ["NonBonded","Expression"], ["Bond2","Expression"],
// ["Bond3","Expression"], ["Bond4","Expression"] and ["External","Expression"]. Each is configurable
// (component_registry.hpp): configure() parses "parameters.energy", takes every name in it as an
// input (r, theta, phi, or x, y, z, t), a column of "data" or a key of "parameters" (folded in as a
// number), differentiates it symbolically and compiles the energy and its derivatives into one
// program (src/expression/). The factories upload that program to the backend, build the Params of
// each type pair or bond (expression_potentials.hpp) and hand the program's ownership to the
// interactor. A scene without expressions runs none of this.
#include <memory>
#include <string>
#include <vector>

#include "expression/compiler.hpp"
#include "expression/expression.hpp"
#include "forcefield/expression_compiled.hpp"
#include "forcefield/expression_potentials.hpp"
#include "forcefield/external_interaction.hpp"
#include "forcefield/interactor_tables.hpp"

namespace structmd {

// The reader's side (component_registry.hpp, which engines do not include): the registry entries
// are made in expression_component.cpp.
struct ForceFieldComponent;

// What configure() derives from an entry, for its factory.
struct ExpressionConfig : ComponentConfig {
    std::string path;                     // of parameters.energy, for messages
    std::vector<std::string> inputs;      // r; theta; phi; x, y, z, t
    std::vector<std::string> columns;     // data columns by slot (the Parameter names point here)
    expression::Expression graph;         // the energy and its derivatives, sharing their nodes
    std::vector<int> roots;               // energy, then dU/d inputs[k] for each differentiated input
    expression::Program program;          // computes the roots, in that order

    // The values of the columns of one type pair or bond, by slot.
    std::vector<double> columns_of(const ParameterValues& values) const;
};

// The config of an Expression entry's spec (an internal error if it has none).
const ExpressionConfig& expression_config(const InteractionSpec& spec);

// The entry's expression as the RuntimeSource (expression_compiled.hpp) of the term `potential`.
inline RuntimeSource compiled_source(const ExpressionConfig& config, const std::string& potential) {
    return compiled_expression_source(config.graph, config.roots, config.inputs.size(), config.columns.size(),
                                      potential);
}

// A compiled program in backend memory, in the real type of the term that runs it.
template <class B, class R>
struct UploadedProgram {
    typename B::template Buffer<expression::Instruction> code;
    typename B::template Buffer<R> constants;

    expression::ProgramView<R> view() const {
        return {code.data(), constants.data(), static_cast<int>(code.size())};
    }
};

template <class B, class R>
std::shared_ptr<UploadedProgram<B, R>> upload_program(const B& backend, const expression::Program& program) {
    auto uploaded = std::make_shared<UploadedProgram<B, R>>();
    std::vector<R> constants(program.constants.begin(), program.constants.end());
    if (constants.empty()) constants.push_back(R(0));  // no buffer of size 0
    backend.upload(uploaded->code, program.code.data(), program.code.size());
    backend.upload(uploaded->constants, constants.data(), constants.size());
    return uploaded;
}

template <class R, class Params>
void set_columns(Params& p, const std::vector<double>& columns) {
    for (size_t k = 0; k < columns.size(); ++k) p.columns[k] = R(columns[k]);
}

struct ExpressionPairComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& pair = static_cast<const PairSpec&>(s);
        const ExpressionConfig& config = expression_config(s);
        const double cutOff = pair.shared["cutOff"];
        using Params = InterpretedPair::Params<PairR>;
        auto table = pair_table_of<Params>(pair, build.context, [&](const ParameterValues& v) {
            const std::vector<double> columns = config.columns_of(v);
            Params p{};
            p.cutoff2 = PairR(cutOff * cutOff);
            p.offset = pair.shift ? PairR(-config.program.run({cutOff}, columns)[0]) : PairR(0);
            set_columns<PairR>(p.function, columns);
            return p;
        });
        if constexpr (B::compiles_at_run_time) {
            std::vector<PairR> flat;
            for (const Params& p : table) {
                flat.insert(flat.end(), {p.cutoff2, p.offset});
                append_columns(flat, p.function.columns, config.columns.size());
            }
            auto interactor = std::make_unique<CompiledPairInteraction<B, R, PairR>>(
                build.backend, build.scope(pair), build.listFor(pair),
                compiled_source(config, "ExpressionPair<RuntimeExpression>"), flat,
                static_cast<int>(build.context.ntypes), batches_for(build, pair));
            log_compile_time(build.context.log, s.path, interactor->compile_seconds());
            return interactor;
        } else {
            // Interpreted: every type pair runs the one uploaded program.
            const auto program = upload_program<B, PairR>(build.backend, config.program);
            for (Params& p : table) p.function.program = program->view();
            auto interactor = make_pair_interaction<B, R, InterpretedPair, PairR>(build, pair, table);
            interactor->own(program);
            return interactor;
        }
    }
};

template <int N>
struct ExpressionBondComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);  // for N = 2, 3, 4

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const ExpressionConfig& config = expression_config(s);
        const auto& bond = static_cast<const BondSpec&>(s);
        if constexpr (B::compiles_at_run_time) {
            const auto bonds = bonds_in_group<std::vector<double>>(
                build, bond, [&](const ParameterValues& v) { return config.columns_of(v); });
            std::vector<R> flat;
            for (const std::vector<double>& columns : bonds.params) {
                const std::vector<R> values(columns.begin(), columns.end());
                append_columns(flat, values.data(), values.size());
            }
            auto interactor = std::make_unique<CompiledBondInteraction<B, R, N>>(
                build.backend, build.scope(s), build.context.particles, bonds.members,
                compiled_source(config, "ExpressionBond<" + std::to_string(N) + ", RuntimeExpression>"), flat);
            log_compile_time(build.context.log, s.path, interactor->compile_seconds());
            return interactor;
        } else {
            const auto program = upload_program<B, R>(build.backend, config.program);
            auto interactor = make_bond_interaction<B, R, InterpretedBond<N>>(build, bond, [&](const ParameterValues& v) {
                typename InterpretedBond<N>::template Params<R> p{};
                p.program = program->view();
                set_columns<R>(p, config.columns_of(v));
                return p;
            });
            interactor->own(program);
            return interactor;
        }
    }
};

struct ExpressionExternalComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const ExpressionConfig& config = expression_config(s);
        if constexpr (B::compiles_at_run_time) {
            // No data columns: the Params of the compiled field is one unused real.
            auto interactor = std::make_unique<CompiledExternalInteraction<B, R>>(
                build.backend, build.scope(s), compiled_source(config, "ExpressionExternal<RuntimeExpression>"),
                R(0));
            log_compile_time(build.context.log, s.path, interactor->compile_seconds());
            return interactor;
        } else {
            const auto program = upload_program<B, R>(build.backend, config.program);
            InterpretedExternal::Params<R> params{};
            params.program = program->view();
            auto interactor = std::make_unique<ExternalInteraction<B, R, InterpretedExternal>>(build.backend,
                                                                                              build.scope(s), params);
            interactor->own(program);
            return interactor;
        }
    }
};

}  // namespace structmd
