#pragma once
// The definition of add_builtin_factories (builtin_factories.hpp): one group of components.hpp's list
// visited with FactoryEntries, so that a unit compiles the kernels of its own group alone.
#include "forcefield/builtin_factories.hpp"
#include "forcefield/components.hpp"
#include "forcefield/factory_entries.hpp"

namespace structmd {

template <class B, class R, class PairR, ComponentGroup G>
void add_builtin_factories(Registry<InteractorFactory<B, R>>& registry) {
    FactoryEntries<B, R, PairR> entries;
    visit_component_group<G>(entries);
    for (const InteractorFactory<B, R>& factory : entries.registry.entries()) registry.add(factory);
}

}  // namespace structmd
