#pragma once
// The built-in components' factories of one engine type, made once per process. Each family of the
// list (components.hpp) is built in a translation unit of its own per engine type
// (builtin_factory_family.hpp, instantiated by src/engines/), so no unit compiles every kernel and an
// engine's own unit compiles none.
#include "core/registry.hpp"
#include "forcefield/interactor_build.hpp"

namespace structmd {

// The visitor calls of components.hpp: pair, bond, external and configurable.
enum class ComponentFamily { pairs, bonds, externals, configurables };

// Adds the factories of family F's built-in components to `registry`; defined in
// builtin_factory_family.hpp.
template <class B, class R, class PairR, ComponentFamily F>
void add_builtin_factories(Registry<InteractorFactory<B, R>>& registry);

template <class B, class R, class PairR>
const Registry<InteractorFactory<B, R>>& builtin_interactor_factories() {
    static const Registry<InteractorFactory<B, R>> builtin = [] {
        Registry<InteractorFactory<B, R>> registry;
        add_builtin_factories<B, R, PairR, ComponentFamily::pairs>(registry);
        add_builtin_factories<B, R, PairR, ComponentFamily::bonds>(registry);
        add_builtin_factories<B, R, PairR, ComponentFamily::externals>(registry);
        add_builtin_factories<B, R, PairR, ComponentFamily::configurables>(registry);
        return registry;
    }();
    return builtin;
}

}  // namespace structmd
