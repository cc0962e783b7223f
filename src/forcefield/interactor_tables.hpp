#pragma once
// What the factories of the built-in components (make_interactors.hpp) and of the configurable
// ones (expression_component.hpp) share: the parameter table of a pair term, one entry per ordered
// type pair, the bonds of a bond entry that act in its group, each with its parameters, and the
// table of an external field of per-type parameters.
#include <algorithm>
#include <memory>
#include <vector>

#include "forcefield/bond_interaction.hpp"
#include "forcefield/external_interaction.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/pair_interaction.hpp"

namespace structmd {

// make(values) gives the Params of a type pair from its parameters (the shared ones and its row's).
// Unlisted type pairs take `unlisted`: by default value-initialised parameters (zero cutoff), which
// never interact; a term without per-type-pair parameters gives every type pair the same. A
// batched table (PairSpec::batched) has one ntypes x ntypes block per batch of the context.
template <class Params, class Make>
std::vector<Params> pair_table_of(const PairSpec& pair, const ForceFieldContext& context, Make&& make,
                                  const Params& unlisted = Params{}) {
    const size_t ntypes = context.ntypes;
    if (pair.everyTypePair) return std::vector<Params>(ntypes * ntypes, make(pair.shared));
    const size_t blocks = pair.batched() ? static_cast<size_t>(context.batches) : 1;
    std::vector<Params> table(blocks * ntypes * ntypes, unlisted);
    for (const PairSpec::Row& row : pair.rows) {
        const Params p = make(pair.values_of(row));
        const size_t block = pair.batched() ? static_cast<size_t>(row.batch) * ntypes * ntypes : 0;
        table[block + row.typeI * ntypes + row.typeJ] = p;
        table[block + row.typeJ * ntypes + row.typeI] = p;
    }
    return table;
}

// The particles' batches a pair term's kernels are given: only those of a batched table need them.
template <class B, class R>
const int* batches_for(const InteractorBuild<B, R>& build, const PairSpec& pair) {
    return pair.batched() ? build.context.batch : nullptr;
}

template <class B, class R, class Potential, class PairR>
std::unique_ptr<PairInteraction<B, R, Potential, PairR>> make_pair_interaction(
    const InteractorBuild<B, R>& build, const PairSpec& pair,
    const std::vector<typename Potential::template Params<PairR>>& table) {
    return std::make_unique<PairInteraction<B, R, Potential, PairR>>(
        build.backend, build.scope(pair), build.listFor(pair), table, static_cast<int>(build.context.ntypes),
        batches_for(build, pair));
}

// The bonds of a bond entry that act in its group: N particle indices and one Params each.
template <class Params>
struct BondsInGroup {
    std::vector<int> members;
    std::vector<Params> params;
};

// The bonds of `bond` whose particles all belong to its group, each with make(values) as its Params.
template <class Params, class B, class R, class Make>
BondsInGroup<Params> bonds_in_group(const InteractorBuild<B, R>& build, const BondSpec& bond, Make&& make) {
    const std::vector<uint8_t>* inGroup = bond.group >= 0 ? &build.spec.groups[bond.group].members : nullptr;
    const size_t width = width_of(bond.schema);
    BondsInGroup<Params> bonds;
    ParameterValues values;
    for (size_t b = 0; b * bond.arity < bond.members.size(); ++b) {
        const int* ids = &bond.members[b * bond.arity];
        if (inGroup && !std::all_of(ids, ids + bond.arity, [&](int id) { return (*inGroup)[id]; })) continue;
        bonds.members.insert(bonds.members.end(), ids, ids + bond.arity);
        // data(), not [ ]: a schema of no parameters (an Expression of r alone) has no values at all.
        values.assign(bond.schema, bond.values.data() + b * width);
        bonds.params.push_back(make(values));
    }
    return bonds;
}

// The table of an external entry of per-type parameters (ExternalSpec::perType): one entry per type,
// or per (batch, type) for a batched table, each listed row's Params made by make(values).
struct TypedExternalLayout {
    const ExternalSpec& external;
    size_t ntypes;
    bool batched;
    size_t size;

    template <class B, class R>
    TypedExternalLayout(const InteractorBuild<B, R>& build, const ExternalSpec& e)
        : external(e),
          ntypes(build.context.ntypes),
          batched(!e.rows.empty() && e.rows.front().batch >= 0),
          size(ntypes * (batched ? build.context.batches : 1)) {}

    size_t at(const ExternalSpec::Row& row) const { return (batched ? row.batch * ntypes : 0) + row.type; }

    template <class Params, class Make>
    std::vector<Params> table(Make&& make) const {
        std::vector<Params> table(size);
        for (const ExternalSpec::Row& row : external.rows) table[at(row)] = make(external.values_of(row));
        return table;
    }

    std::vector<uint8_t> listed() const {
        std::vector<uint8_t> listed(size, 0);
        for (const ExternalSpec::Row& row : external.rows) listed[at(row)] = 1;
        return listed;
    }

    template <class Potential, class B, class R>
    std::unique_ptr<TypedExternalInteraction<B, R, Potential>> make(
        const InteractorBuild<B, R>& build, const std::vector<typename Potential::template Params<R>>& table) const {
        return std::make_unique<TypedExternalInteraction<B, R, Potential>>(
            build.backend, build.scope(external), table, listed(), batched ? build.context.batch : nullptr,
            static_cast<int>(ntypes));
    }
};

template <class B, class R, class Potential, class Make>
std::unique_ptr<BondInteraction<B, R, Potential>> make_bond_interaction(const InteractorBuild<B, R>& build,
                                                                        const BondSpec& bond, Make&& make) {
    const auto bonds = bonds_in_group<typename Potential::template Params<R>>(build, bond, make);
    return std::make_unique<BondInteraction<B, R, Potential>>(build.backend, build.scope(bond),
                                                              build.context.particles, bonds.members, bonds.params);
}

}  // namespace structmd
