#pragma once
// Builds an engine's force field from the plain spec. Each component's factory comes from the
// built-in list (components.hpp), made once per engine type; a spec names its component by key, so
// nothing here knows a potential by name.
#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/registry.hpp"
#include "forcefield/bond_interaction.hpp"
#include "forcefield/components.hpp"
#include "forcefield/external_interaction.hpp"
#include "forcefield/force_field.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/interactor_tables.hpp"
#include "forcefield/pair_interaction.hpp"

namespace structmd {

// Pair terms evaluate in PairR (float for mixed precision); everything else in R. WithHessian: the
// factories can also make each term's parameters in dual numbers (core/dual.hpp), which needs
// functors that call their math functions unqualified; the built-in ones do, a plugin's need not.
template <class B, class R, class PairR, bool WithHessian = true>
struct FactoryEntries {
    using Build = InteractorBuild<B, R>;
    Registry<InteractorFactory<B, R>> registry;

    template <class Potential>
    void pair(ComponentKey key) {
        registry.add({std::move(key), [](const Build& build, const InteractionSpec& s) -> std::unique_ptr<Interactor<B, R>> {
                          const auto& pair = static_cast<const PairSpec&>(s);
                          const Constants& constants = build.context.constants;
                          // The table in real type T (PairR, or its dual numbers for the Hessian).
                          const auto tableIn = [&](auto real) {
                              using T = decltype(real);
                              using Params = typename Potential::template Params<T>;
                              Params unlisted{};
                              if constexpr (acts_on_unlisted_pairs<Potential>::value)
                                  unlisted = Potential::template make_unlisted_pair_params<T>(
                                      pair.shared, constants, pair.cutOffFactor, pair.shift);
                              return pair_table_of<Params>(
                                  pair, build.context,
                                  [&](const ParameterValues& v) {
                                      return Potential::template make_pair_params<T>(v, constants, pair.cutOffFactor,
                                                                                     pair.shift);
                                  },
                                  unlisted);
                          };
                          auto interactor = make_pair_interaction<B, R, Potential, PairR>(build, pair, tableIn(PairR{}));
                          if constexpr (WithHessian)
                              if (build.context.hessian) interactor->enable_hessian(tableIn(Dual<PairR>{}));
                          return interactor;
                      }});
    }

    template <class Potential>
    void bond(ComponentKey key, const std::vector<std::string>& = {}) {
        registry.add({std::move(key), [](const Build& build, const InteractionSpec& s) -> std::unique_ptr<Interactor<B, R>> {
                          const Constants& constants = build.context.constants;
                          const auto& bond = static_cast<const BondSpec&>(s);
                          auto interactor = make_bond_interaction<B, R, Potential>(
                              build, bond, [&](const ParameterValues& v) {
                                  return Potential::template make_params<R>(v, constants);
                              });
                          if constexpr (WithHessian)
                              if (build.context.hessian)
                                  interactor->enable_hessian(
                                      bonds_in_group<typename Potential::template Params<Dual<R>>>(
                                      build, bond,
                                      [&](const ParameterValues& v) {
                                          return Potential::template make_params<Dual<R>>(v, constants);
                                      })
                                      .params);
                          return interactor;
                      }});
    }

    template <class Potential>
    void external(ComponentKey key) {
        registry.add({std::move(key), [](const Build& build, const InteractionSpec& s) -> std::unique_ptr<Interactor<B, R>> {
                          const auto& external = static_cast<const ExternalSpec&>(s);
                          const Constants& constants = build.context.constants;
                          if constexpr (has_type_parameters<Potential>::value) {
                              const TypedExternalLayout layout(build, external);
                              const auto tableIn = [&](auto real) {
                                  using T = decltype(real);
                                  return layout.template table<typename Potential::template Params<T>>(
                                      [&](const ParameterValues& v) {
                                          return Potential::template make_params<T>(v, constants);
                                      });
                              };
                              auto interactor = layout.template make<Potential>(build, tableIn(R{}));
                              if constexpr (WithHessian)
                                  if (build.context.hessian) interactor->enable_hessian(tableIn(Dual<R>{}));
                              return interactor;
                          } else {
                              auto interactor = std::make_unique<ExternalInteraction<B, R, Potential>>(
                                  build.backend, build.scope(external),
                                  Potential::template make_params<R>(external.values, constants));
                              if constexpr (WithHessian)
                                  if (build.context.hessian)
                                      interactor->enable_hessian(
                                          Potential::template make_params<Dual<R>>(external.values, constants));
                              return interactor;
                          }
                      }});
    }

    template <class Component>
    void configurable(ComponentKey key) {
        registry.add({std::move(key), &Component::template make_interactor<B, R, PairR>});
    }
};

template <class B, class R, class PairR>
const Registry<InteractorFactory<B, R>>& builtin_interactor_factories() {
    static const Registry<InteractorFactory<B, R>> builtin = [] {
        FactoryEntries<B, R, PairR> entries;
        visit_builtin_forcefield(entries);
        return std::move(entries.registry);
    }();
    return builtin;
}

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
                                                       context.model);
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
