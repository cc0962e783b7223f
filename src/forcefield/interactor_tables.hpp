#pragma once
// What the factories of the built-in components (make_interactors.hpp) and of the configurable
// ones (expression_component.hpp) share: the parameter table of a pair term, one entry per ordered
// type pair, and the bonds of a bond entry that act in its group, each with its parameters.
#include <algorithm>
#include <memory>
#include <vector>

#include "forcefield/bond_interaction.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/pair_interaction.hpp"

namespace structmd {

// make(values) gives the Params of a type pair from its parameters (the shared ones and its row's).
// Unlisted type pairs take `unlisted`: by default value-initialised parameters (zero cutoff), which
// never interact; a term without per-type-pair parameters gives every type pair the same.
template <class Params, class Make>
std::vector<Params> pair_table_of(const PairSpec& pair, size_t ntypes, Make&& make, const Params& unlisted = Params{}) {
    if (pair.everyTypePair) return std::vector<Params>(ntypes * ntypes, make(pair.shared));
    std::vector<Params> table(ntypes * ntypes, unlisted);
    for (const PairSpec::Row& row : pair.rows) {
        const Params p = make(pair.values_of(row));
        table[row.typeI * ntypes + row.typeJ] = p;
        table[row.typeJ * ntypes + row.typeI] = p;
    }
    return table;
}

template <class B, class R, class Potential, class PairR>
std::unique_ptr<PairInteraction<B, R, Potential, PairR>> make_pair_interaction(
    const InteractorBuild<B, R>& build, const PairSpec& pair,
    const std::vector<typename Potential::template Params<PairR>>& table) {
    return std::make_unique<PairInteraction<B, R, Potential, PairR>>(build.backend, build.scope(pair),
                                                                     build.listFor(pair), table,
                                                                     static_cast<int>(build.context.ntypes));
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
        values.assign(bond.schema, &bond.values[b * width]);
        bonds.params.push_back(make(values));
    }
    return bonds;
}

template <class B, class R, class Potential, class Make>
std::unique_ptr<BondInteraction<B, R, Potential>> make_bond_interaction(const InteractorBuild<B, R>& build,
                                                                        const BondSpec& bond, Make&& make) {
    const auto bonds = bonds_in_group<typename Potential::template Params<R>>(build, bond, make);
    return std::make_unique<BondInteraction<B, R, Potential>>(build.backend, build.scope(bond),
                                                              build.context.particles, bonds.members, bonds.params);
}

}  // namespace structmd
