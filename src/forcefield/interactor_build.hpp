#pragma once
// What an engine's interactor factories are given (make_interactors.hpp builds the force field
// with them): the backend, the engine data, the spec and the force field under construction.
// Configurable components (component_registry.hpp) write their factory against this alone.
#include <algorithm>
#include <functional>
#include <memory>
#include <vector>

#include "core/registry.hpp"
#include "forcefield/bond_interaction.hpp"
#include "forcefield/force_field.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/pair_potential.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

// The engine-side data a force field is built against.
struct ForceFieldContext {
    size_t ntypes = 0;
    int64_t particles = 0;
    Constants constants;
    const int* batch = nullptr;  // backend arrays by particle, or null where not needed
    const int* model = nullptr;
};

// What a factory is given: the backend, the engine data, and the force field under construction
// (its groups and the list a pair term runs over).
template <class B, class R>
struct InteractorBuild {
    const B& backend;
    const ForceFieldSpec& spec;
    const ForceFieldContext& context;
    ForceField<B, R>& forceField;
    std::function<std::shared_ptr<VerletList<B, R>>(const PairSpec&)> listFor;

    InteractorScope scope(const InteractionSpec& s) const {
        return InteractorScope{s.name, s.startStep, s.endStep, s.group >= 0 ? forceField.group(s.group) : nullptr};
    }
};

// One entry per component: makes the interactor of an InteractionSpec of the component's kind
// (a PairSpec, BondSpec or ExternalSpec).
template <class B, class R>
struct InteractorFactory {
    ComponentKey key;
    std::function<std::unique_ptr<Interactor<B, R>>(const InteractorBuild<B, R>&, const InteractionSpec&)> make;
};

// The interactor of a bond entry: its bonds whose particles all lie in the entry's group, each with
// the Params that params_of(b) gives for bond b of the spec.
template <class Potential, class B, class R, class ParamsOf>
std::unique_ptr<Interactor<B, R>> make_bond_interaction(const InteractorBuild<B, R>& build, const BondSpec& bond,
                                                        ParamsOf params_of) {
    using Params = typename Potential::template Params<R>;
    const std::vector<uint8_t>* inGroup = bond.group >= 0 ? &build.spec.groups[bond.group].members : nullptr;
    std::vector<int> members;
    std::vector<Params> params;
    for (size_t b = 0; b * bond.arity < bond.members.size(); ++b) {
        const int* ids = &bond.members[b * bond.arity];
        if (inGroup && !std::all_of(ids, ids + bond.arity, [&](int id) { return (*inGroup)[id]; })) continue;
        members.insert(members.end(), ids, ids + bond.arity);
        params.push_back(params_of(b));
    }
    return std::make_unique<BondInteraction<B, R, Potential>>(build.backend, build.scope(bond),
                                                              build.context.particles, members, params);
}

}  // namespace structmd
