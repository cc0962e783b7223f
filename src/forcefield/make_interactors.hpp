#pragma once
// Builds an engine's force field from the plain spec. This is where a potential's name meets its
// functor: each family maps to one type in the tables below, and a new potential adds a line there.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "forcefield/bond_interaction.hpp"
#include "forcefield/constant_force_bond.hpp"
#include "forcefield/debye_huckel.hpp"
#include "forcefield/dihedral.hpp"
#include "forcefield/external_constant_force.hpp"
#include "forcefield/external_interaction.hpp"
#include "forcefield/fene_bond.hpp"
#include "forcefield/fixed_harmonic.hpp"
#include "forcefield/force_field.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/gaussian_bond.hpp"
#include "forcefield/harmonic_angle.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "forcefield/kratky_porod.hpp"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/lennard_jones_general.hpp"
#include "forcefield/lennard_jones_wca.hpp"
#include "forcefield/morse.hpp"
#include "forcefield/pair_interaction.hpp"
#include "forcefield/plates.hpp"
#include "forcefield/spherical_shell.hpp"
#include "forcefield/steric.hpp"

namespace structmd {

template <class T>
struct Tag {
    using type = T;
};

// Calls build(Tag<Functor>{}) for the functor of a pair family; false if the family is unknown.
template <class Build>
bool with_pair_potential(const std::string& family, Build&& build) {
    if (family == "LennardJonesType1") return build(Tag<LennardJonesType1>{}), true;
    if (family == "LennardJonesType2") return build(Tag<LennardJonesType2>{}), true;
    if (family == "LennardJonesType3") return build(Tag<LennardJonesType3>{}), true;
    if (family == "WCAType1") return build(Tag<WCAType1>{}), true;
    if (family == "WCAType2") return build(Tag<WCAType2>{}), true;
    if (family == "WCAType3") return build(Tag<WCAType3>{}), true;
    if (family == "GeneralLennardJonesType1") return build(Tag<GeneralLennardJonesType1>{}), true;
    if (family == "GeneralLennardJonesType2") return build(Tag<GeneralLennardJonesType2>{}), true;
    if (family == "GeneralLennardJonesType3") return build(Tag<GeneralLennardJonesType3>{}), true;
    if (family == "Steric6") return build(Tag<Steric6>{}), true;
    if (family == "Steric12") return build(Tag<Steric12>{}), true;
    if (family == "DebyeHuckel") return build(Tag<DebyeHuckel>{}), true;
    return false;
}

// Calls build(Tag<Functor>{}) for the functor of a bonded family (bond_potential.hpp).
template <class Build>
bool with_bond_potential(const std::string& family, Build&& build) {
    if (family == "Harmonic") return build(Tag<RadialBond<HarmonicBond>>{}), true;
    if (family == "Fene") return build(Tag<RadialBond<FeneBond>>{}), true;
    if (family == "Morse") return build(Tag<RadialBond<MorseBond>>{}), true;
    if (family == "LennardJonesType1") return build(Tag<RadialBond<LennardJonesType1>>{}), true;
    if (family == "LennardJonesType2") return build(Tag<RadialBond<LennardJonesType2>>{}), true;
    if (family == "LennardJonesType3") return build(Tag<RadialBond<LennardJonesType3>>{}), true;
    if (family == "Gaussian") return build(Tag<RadialBond<GaussianBond>>{}), true;
    if (family == "Steric6") return build(Tag<RadialBond<Steric6>>{}), true;
    if (family == "Steric12") return build(Tag<RadialBond<Steric12>>{}), true;
    if (family == "DebyeHuckel") return build(Tag<RadialBond<DebyeHuckel>>{}), true;
    if (family == "HarmonicAngular") return build(Tag<HarmonicAngle>{}), true;
    if (family == "KratkyPorod") return build(Tag<KratkyPorod>{}), true;
    if (family == "Dihedral") return build(Tag<Dihedral>{}), true;
    if (family == "Dihedral4") return build(Tag<Dihedral4>{}), true;
    if (family == "FixedHarmonic") return build(Tag<FixedHarmonic>{}), true;
    if (family == "ConstantForce") return build(Tag<ConstantForceBond>{}), true;
    return false;
}

// Calls build(params) with the functor's parameters for an external family (external_potential.hpp),
// from the reader's values in their documented order.
template <class R, class Build>
bool with_external_potential(const std::string& family, const std::vector<double>& v, Build&& build) {
    if (family == "ConstantForce")
        return build(Tag<ExternalConstantForce>{}, ExternalConstantForce::make_params<R>({v[0], v[1], v[2]})), true;
    if (family == "Plates")
        return build(Tag<Plates>{}, Plates::make_params<R>(v[0], v[1], v[2], v[3], v[4], v[5])), true;
    if (family == "SphericalShell")
        return build(Tag<SphericalShell>{},
                     SphericalShell::make_params<R>({v[0], v[1], v[2]}, v[3], v[4], v[5], v[6], v[7], v[8])),
               true;
    return false;
}

// The parameter table of a pair term: one entry per ordered type pair. Unlisted type pairs keep
// value-initialised parameters (zero cutoff) and so never interact.
template <class Potential, class R>
std::vector<typename Potential::template Params<R>> pair_table(const PairSpec& pair, size_t ntypes,
                                                               const Constants& constants) {
    using Params = typename Potential::template Params<R>;
    std::vector<Params> table(ntypes * ntypes, Params{});
    if constexpr (UsesCharges<Potential>::value) {
        const Params p = Potential::template make_params<R>(pair.dielectricConstant, pair.debyeLength,
                                                            pair.cutOffFactor * pair.debyeLength, constants, pair.shift);
        std::fill(table.begin(), table.end(), p);
    } else {
        for (const PairSpec::Row& row : pair.rows) {
            const Params p = Potential::template make_pair_params<R>(row.epsilon, row.sigma,
                                                                    pair.cutOffFactor * row.sigma, pair.shift);
            table[row.typeI * ntypes + row.typeJ] = p;
            table[row.typeJ * ntypes + row.typeI] = p;
        }
    }
    return table;
}

// The distance beyond which a pair term is zero, read from its table: a WCA term acts only up to
// its minimum whatever cutOffFactor says, so its list can be much smaller.
template <class R>
double acting_cutoff(const PairSpec& pair, size_t ntypes, const Constants& constants) {
    double cutoff2 = 0.0;
    with_pair_potential(pair.potential, [&](auto tag) {
        using Potential = typename decltype(tag)::type;
        for (const auto& p : pair_table<Potential, double>(pair, ntypes, constants))
            cutoff2 = std::max(cutoff2, static_cast<double>(p.cutoff2));
    });
    return std::sqrt(cutoff2);
}

// The engine-side data a force field is built against.
struct ForceFieldContext {
    size_t ntypes = 0;
    int64_t particles = 0;
    Constants constants;
    const int* batch = nullptr;  // backend arrays by particle, or null where not needed
    const int* model = nullptr;
};

// Pair terms evaluate in PairR (float for mixed precision); everything else in R.
template <class B, class R, class PairR>
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
                cutoff = std::max(cutoff, acting_cutoff<R>(other, context.ntypes, context.constants));
        const PairCondition condition = pair.subList == "nonExcluded" ? PairCondition::nonExcluded
                                        : pair.subList == "intra"     ? PairCondition::intra
                                        : pair.subList == "inter"     ? PairCondition::inter
                                                                      : PairCondition::all;
        auto list = std::make_shared<VerletList<B, R>>(backend, cutoff, entry.verletFactor, condition, entry.excluded,
                                                       context.batch, context.model);
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
                const auto table = pair_table<Potential, PairR>(pair, context.ntypes, context.constants);
                ff.add(std::make_unique<PairInteraction<B, R, Potential, PairR>>(
                    backend, scope(pair), list_for(pair), table, static_cast<int>(context.ntypes)));
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
            const bool known = with_external_potential<R>(external.potential, external.values, [&](auto tag, auto params) {
                using Potential = typename decltype(tag)::type;
                ff.add(std::make_unique<ExternalInteraction<B, R, Potential>>(backend, scope(external), params));
            });
            if (!known)
                throw Error(STRUCTMD_ERR_INTERNAL, external.path + ": external potential without an implementation");
        }
    }
    return ff;
}

}  // namespace structmd
