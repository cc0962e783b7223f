#pragma once
// How a factory is made for each kind of built-in or plugin component (FactoryEntries: the visitor of
// components.hpp's list on the engine side). Heavy: it instantiates a component's kernels, so only the
// units that build factories include it (engines/, a plugin).
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "forcefield/all_pairs_interaction.hpp"
#include "forcefield/bond_interaction.hpp"
#include "forcefield/external_interaction.hpp"
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
                          // An ["NBody", "all"] list: every pair, no list and no second derivatives.
                          if (build.spec.lists[pair.list].allPairs)
                              return std::make_unique<AllPairsInteraction<B, R, Potential, PairR>>(
                                  build.backend, build.scope(pair), tableIn(PairR{}),
                                  static_cast<int>(build.context.ntypes), batches_for(build, pair), build.context.batch);
                          // The reader gives a term of no cutoff an ["NBody", "all"] list only.
                          if constexpr (has_infinite_range<Potential>::value) {
                              throw Error(STRUCTMD_ERR_INTERNAL, pair.path + ": a term of no cutoff over a Verlet list");
                          } else {
                              auto interactor =
                                  make_pair_interaction<B, R, Potential, PairR>(build, pair, tableIn(PairR{}));
                              if constexpr (WithHessian)
                                  if (build.context.hessian) interactor->enable_hessian(tableIn(Dual<PairR>{}));
                              return interactor;
                          }
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

}  // namespace structmd
