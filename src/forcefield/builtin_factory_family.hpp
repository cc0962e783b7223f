#pragma once
// The definition of add_builtin_factories (builtin_factories.hpp): components.hpp's list visited with
// FactoryEntries, keeping the calls of one family. The other calls only name their types, so a unit
// compiles the kernels of its own family alone.
#include "forcefield/builtin_factories.hpp"
#include "forcefield/components.hpp"
#include "forcefield/factory_entries.hpp"

namespace structmd {

template <class B, class R, class PairR, ComponentFamily F>
struct FamilyEntries {
    FactoryEntries<B, R, PairR> entries;

    template <class Potential>
    void pair(ComponentKey key) {
        if constexpr (F == ComponentFamily::pairs) entries.template pair<Potential>(std::move(key));
    }
    template <class Potential>
    void bond(ComponentKey key, const std::vector<std::string>& common = {}) {
        if constexpr (F == ComponentFamily::bonds) entries.template bond<Potential>(std::move(key), common);
    }
    template <class Potential>
    void external(ComponentKey key) {
        if constexpr (F == ComponentFamily::externals) entries.template external<Potential>(std::move(key));
    }
    template <class Component>
    void configurable(ComponentKey key) {
        if constexpr (F == ComponentFamily::configurables) entries.template configurable<Component>(std::move(key));
    }
};

template <class B, class R, class PairR, ComponentFamily F>
void add_builtin_factories(Registry<InteractorFactory<B, R>>& registry) {
    FamilyEntries<B, R, PairR, F> family;
    visit_builtin_forcefield(family);
    for (const InteractorFactory<B, R>& factory : family.entries.registry.entries()) registry.add(factory);
}

}  // namespace structmd
