#pragma once
// The built-in components' factories of one engine type, made once per process. Each group of the
// list (components.hpp, component_groups.hpp) is built in a translation unit of its own per engine
// type (builtin_factory_group.hpp, instantiated by src/CMakeLists.txt's engine units), so no unit
// compiles every kernel and an engine's own unit compiles none.
#include "core/registry.hpp"
#include "forcefield/component_groups.hpp"
#include "forcefield/interactor_build.hpp"

namespace structmd {

// Adds the factories of group G's built-in components to `registry`; defined in
// builtin_factory_group.hpp.
template <class B, class R, class PairR, ComponentGroup G>
void add_builtin_factories(Registry<InteractorFactory<B, R>>& registry);

template <class B, class R, class PairR>
const Registry<InteractorFactory<B, R>>& builtin_interactor_factories() {
    static const Registry<InteractorFactory<B, R>> builtin = [] {
        Registry<InteractorFactory<B, R>> registry;
        for_each_component_group(
            [&registry](auto group) { add_builtin_factories<B, R, PairR, decltype(group)::value>(registry); });
        return registry;
    }();
    return builtin;
}

}  // namespace structmd
