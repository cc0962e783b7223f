#pragma once
// Builds an engine's force field from the plain spec. This is where a potential's name meets its
// functor: each family maps to one type in the tables below, and a new potential adds a line there.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "forcefield/bond_interaction.hpp"
#include "forcefield/external_interaction.hpp"
#include "forcefield/fene_bond.hpp"
#include "forcefield/force_field.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/pair_interaction.hpp"

namespace structmd {

template <class T>
struct Tag {
    using type = T;
};

// Calls build(Tag<Functor>{}) for the functor of a pair family; false if the family is unknown.
template <class Build>
bool with_pair_potential(const std::string& family, Build&& build) {
    if (family == "LennardJonesType1") return build(Tag<LennardJonesType1>{}), true;
    return false;
}

// Calls build(Tag<Functor>{}) for the functor of a bonded family (bond_potential.hpp).
template <class Build>
bool with_bond_potential(const std::string& family, Build&& build) {
    if (family == "Harmonic") return build(Tag<RadialBond<HarmonicBond>>{}), true;
    if (family == "Fene") return build(Tag<RadialBond<FeneBond>>{}), true;
    return false;
}

// Calls build(Tag<Functor>{}) for the functor of an external family (external_potential.hpp).
template <class Build>
bool with_external_potential(const std::string&, Build&&) {
    return false;
}

// The engine-side data a force field is built against.
struct ForceFieldContext {
    size_t ntypes = 0;
    int64_t particles = 0;
    Constants constants;
    const int* batch = nullptr;  // backend arrays by particle, or null where not needed
    const int* model = nullptr;
};

template <class B, class R>
ForceField<B, R> make_interactors(const B& backend, const ForceFieldSpec& spec, const ForceFieldContext& context) {
    ForceField<B, R> ff;
    for (const GroupSpec& group : spec.groups) ff.add_group(backend, group.members);
    auto scope = [&](const InteractionSpec& s) {
        return InteractorScope{s.name, s.startStep, s.endStep, s.group >= 0 ? ff.group(s.group) : nullptr};
    };

    // One list per (list entry, condition) that some pair term uses; its cutoff is the largest of its
    // users'. A scene without pair terms builds no list.
    std::vector<std::pair<std::string, std::shared_ptr<VerletList<B, R>>>> lists;
    auto list_for = [&](const PairSpec& pair) {
        const std::string key = std::to_string(pair.list) + "/" + pair.subList;
        for (const auto& [k, list] : lists)
            if (k == key) return list;
        const NeighbourListSpec& entry = spec.lists[pair.list];
        double cutoff = entry.minimumCutoff;
        for (const PairSpec& other : spec.pairs)
            if (other.list == pair.list && other.subList == pair.subList)
                cutoff = std::max(cutoff, other.largest_cutoff());
        const PairCondition condition = pair.subList == "nonExcluded" ? PairCondition::nonExcluded
                                        : pair.subList == "intra"     ? PairCondition::intra
                                        : pair.subList == "inter"     ? PairCondition::inter
                                                                      : PairCondition::all;
        auto list = std::make_shared<VerletList<B, R>>(backend, entry.name + "/" + pair.subList, cutoff,
                                                       entry.verletFactor, condition, entry.excluded, context.batch,
                                                       context.model);
        lists.emplace_back(key, list);
        ff.add_list(list);
        return list;
    };

    // Interactors in document order, so energy terms and sums keep one order.
    size_t nextPair = 0, nextBond = 0, nextExternal = 0;
    for (const std::string& name : spec.entryNames) {
        if (nextPair < spec.pairs.size() && spec.pairs[nextPair].name == name) {
            const PairSpec& pair = spec.pairs[nextPair++];
            const bool known = with_pair_potential(pair.potential, [&](auto tag) {
                using Potential = typename decltype(tag)::type;
                using Params = typename Potential::template Params<R>;
                // Unlisted type pairs keep a zero cutoff and so never interact.
                std::vector<Params> table(context.ntypes * context.ntypes, Params{});
                for (const PairSpec::Row& row : pair.rows) {
                    const Params p = Potential::template make_pair_params<R>(
                        row.epsilon, row.sigma, pair.cutOffFactor * row.sigma, pair.shift);
                    table[row.typeI * context.ntypes + row.typeJ] = p;
                    table[row.typeJ * context.ntypes + row.typeI] = p;
                }
                ff.add(std::make_unique<PairInteraction<B, R, Potential>>(backend, scope(pair), list_for(pair), table,
                                                                          static_cast<int>(context.ntypes)));
            });
            if (!known) throw Error(STRUCTMD_ERR_INTERNAL, pair.path + ": pair potential without an implementation");
        } else if (nextBond < spec.bonds.size() && spec.bonds[nextBond].name == name) {
            const BondSpec& bond = spec.bonds[nextBond++];
            const bool known = with_bond_potential(bond.potential, [&](auto tag) {
                using Potential = typename decltype(tag)::type;
                using Params = typename Potential::template Params<R>;
                std::vector<int> members;
                std::vector<Params> params;
                const std::vector<uint8_t>* inGroup = bond.group >= 0 ? &spec.groups[bond.group].members : nullptr;
                for (size_t b = 0; b * bond.arity < bond.members.size(); ++b) {
                    const int* ids = &bond.members[b * bond.arity];
                    if (inGroup && !std::all_of(ids, ids + bond.arity, [&](int id) { return (*inGroup)[id]; }))
                        continue;
                    members.insert(members.end(), ids, ids + bond.arity);
                    params.push_back(
                        Potential::template make_params<R>(&bond.params[b * bond.parameterCount], context.constants));
                }
                ff.add(std::make_unique<BondInteraction<B, R, Potential>>(backend, scope(bond), context.particles,
                                                                          members, params));
            });
            if (!known) throw Error(STRUCTMD_ERR_INTERNAL, bond.path + ": bonded potential without an implementation");
        } else if (nextExternal < spec.externals.size() && spec.externals[nextExternal].name == name) {
            const ExternalSpec& external = spec.externals[nextExternal++];
            const bool known = with_external_potential(external.potential, [&](auto tag) {
                using Potential = typename decltype(tag)::type;
                ff.add(std::make_unique<ExternalInteraction<B, R, Potential>>(
                    backend, scope(external), Potential::template make_params<R>(external.values.data())));
            });
            if (!known)
                throw Error(STRUCTMD_ERR_INTERNAL, external.path + ": external potential without an implementation");
        }
    }
    return ff;
}

}  // namespace structmd
