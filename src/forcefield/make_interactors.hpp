#pragma once
// Builds an engine's force field from the plain spec. This is where a potential's name meets its
// functor; a new potential adds a line here.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "forcefield/bond2_interaction.hpp"
#include "forcefield/force_field.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/fene_bond.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/pair_interaction.hpp"

namespace structmd {

template <class B, class R, class Potential>
std::unique_ptr<Interactor<B, R>> make_pair(const B& backend, const PairSpec& spec, size_t ntypes,
                                            std::shared_ptr<VerletList<B, R>> list) {
    using Params = typename Potential::template Params<R>;
    // Unlisted type pairs keep a zero cutoff and so never interact.
    std::vector<Params> table(ntypes * ntypes, Params{});
    for (const PairSpec::Row& row : spec.rows) {
        const Params p = Potential::template make_params<R>(row.epsilon, row.sigma, spec.cutOffFactor * row.sigma,
                                                            spec.shift);
        table[row.typeI * ntypes + row.typeJ] = p;
        table[row.typeJ * ntypes + row.typeI] = p;
    }
    return std::make_unique<PairInteraction<B, R, Potential>>(backend, spec.name, std::move(list), table,
                                                              static_cast<int>(ntypes));
}

template <class B, class R, class Potential>
std::unique_ptr<Interactor<B, R>> make_bond2(const B& backend, const BondSpec& spec, int64_t particles) {
    using Params = typename Potential::template Params<R>;
    std::vector<Params> params;
    for (size_t b = 0; b < spec.ends.size() / 2; ++b)
        params.push_back(Potential::template make_params<R>(&spec.params[b * spec.parameterCount]));
    return std::make_unique<Bond2Interaction<B, R, Potential>>(backend, spec.name, particles, spec.ends, params);
}

template <class B, class R>
ForceField<B, R> make_interactors(const B& backend, const ForceFieldSpec& spec, size_t ntypes, int64_t particles) {
    ForceField<B, R> ff;
    // A list is built only when some pair term uses it; its cutoff is the largest of its users'.
    std::vector<std::shared_ptr<VerletList<B, R>>> lists(spec.lists.size());
    for (size_t l = 0; l < spec.lists.size(); ++l) {
        double cutoff = spec.lists[l].minimumCutoff;
        bool used = false;
        for (const PairSpec& pair : spec.pairs)
            if (pair.list == static_cast<int>(l)) {
                cutoff = std::max(cutoff, pair.largest_cutoff());
                used = true;
            }
        if (!used || cutoff <= 0.0) continue;
        lists[l] = std::make_shared<VerletList<B, R>>(backend, spec.lists[l].name, cutoff, spec.lists[l].verletFactor);
        ff.add_list(lists[l]);
    }
    // Interactors in document order, so energy terms and sums keep one order.
    size_t nextPair = 0, nextBond = 0;
    for (const std::string& name : spec.entryNames) {
        if (nextPair < spec.pairs.size() && spec.pairs[nextPair].name == name) {
            const PairSpec& pair = spec.pairs[nextPair++];
            if (pair.potential == "LennardJonesType1")
                ff.add(make_pair<B, R, LennardJonesType1>(backend, pair, ntypes, lists[pair.list]));
            else
                throw Error(STRUCTMD_ERR_INTERNAL, pair.path + ": pair potential without an implementation");
        } else if (nextBond < spec.bonds.size() && spec.bonds[nextBond].name == name) {
            const BondSpec& bond = spec.bonds[nextBond++];
            if (bond.potential.rfind("Harmonic", 0) == 0)
                ff.add(make_bond2<B, R, HarmonicBond>(backend, bond, particles));
            else if (bond.potential.rfind("Fene", 0) == 0)
                ff.add(make_bond2<B, R, FeneBond>(backend, bond, particles));
            else
                throw Error(STRUCTMD_ERR_INTERNAL, bond.path + ": bond potential without an implementation");
        }
    }
    return ff;
}

}  // namespace structmd
