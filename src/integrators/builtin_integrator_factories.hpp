#pragma once
// The built-in integrators' factories (make_integrator.hpp declares builtin_integrator_factories):
// the list of integrators.hpp visited once per engine type. Heavy: only the units that build them
// include it.
#include <utility>

#include "integrators/integrator_factory_entries.hpp"
#include "integrators/integrators.hpp"
#include "integrators/make_integrator.hpp"

namespace structmd {

template <class B, class R>
const Registry<IntegratorFactory<B, R>>& builtin_integrator_factories() {
    static const Registry<IntegratorFactory<B, R>> builtin = [] {
        IntegratorFactoryEntries<B, R> entries;
        visit_builtin_integrators(entries);
        return std::move(entries.registry);
    }();
    return builtin;
}

}  // namespace structmd
