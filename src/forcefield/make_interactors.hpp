#pragma once
// Builds an engine's force field from the plain spec with the factories it is given (the built-in
// ones, builtin_factories.hpp, and a handle's plugins'); a spec names its component by key, so
// nothing here knows a potential by name.
#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/registry.hpp"
#include "forcefield/force_field.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor_build.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

// `groupsOf`: a force field of the same groups whose group buffers the new one shares (the force
// field made again with new parameters); null: the groups are uploaded.
template <class B, class R>
ForceField<B, R> make_interactors(const B& backend, const ForceFieldSpec& spec, const ForceFieldContext& context,
                                  const Registry<InteractorFactory<B, R>>& factories,
                                  const ForceField<B, R>* groupsOf = nullptr) {
    ForceField<B, R> ff;
    if (groupsOf)
        ff.share_groups(*groupsOf);
    else
        for (const GroupSpec& group : spec.groups) ff.add_group(backend, group.members);

    // One list per (list entry, condition) that some pair term uses; its cutoff is the largest of its
    // users'. A scene without pair terms builds no list.
    std::vector<std::shared_ptr<VerletList<B, R>>> lists;
    std::vector<std::pair<int, PairCondition>> listKeys;
    auto listFor = [&](const PairSpec& pair) {
        const std::pair<int, PairCondition> key{pair.list, pair.condition};
        for (size_t k = 0; k < listKeys.size(); ++k)
            if (listKeys[k] == key) return lists[k];
        const NeighbourListSpec& entry = spec.lists[pair.list];
        double cutoff = entry.minimumCutoff;
        for (const PairSpec& other : spec.pairs)
            if (other.list == pair.list && other.condition == pair.condition) cutoff = std::max(cutoff, other.cutoff);
        auto list = std::make_shared<VerletList<B, R>>(backend, cutoff, entry.verletFactor, pair.condition,
                                                       entry.filterInputs, context.batch, context.batches,
                                                       context.model, spec.clusterPairs);
        lists.push_back(list);
        listKeys.push_back(key);
        ff.add_list(list);
        return list;
    };
    const InteractorBuild<B, R> build{backend, spec, context, ff, listFor};
    const auto add = [&](const InteractionSpec& s) {
        const InteractorFactory<B, R>* factory = factories.find(s.key);
        if (!factory) throw Error(STRUCTMD_ERR_INTERNAL, s.path + ": " + s.key.text() + " has no implementation");
        ff.add(factory->make(build, s));
    };

    // Interactors in document order, so energy terms and sums keep one order.
    size_t nextPair = 0, nextBond = 0, nextExternal = 0;
    for (const std::string& name : spec.entryNames) {
        if (nextPair < spec.pairs.size() && spec.pairs[nextPair].name == name)
            add(spec.pairs[nextPair++]);
        else if (nextBond < spec.bonds.size() && spec.bonds[nextBond].name == name)
            add(spec.bonds[nextBond++]);
        else if (nextExternal < spec.externals.size() && spec.externals[nextExternal].name == name)
            add(spec.externals[nextExternal++]);
    }
    return ff;
}

}  // namespace structmd
