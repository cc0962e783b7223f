#pragma once
// The visitor of integrators.hpp's list that makes a factory per entry: builtin_integrator_factories
// visits the whole list with it; a copy of the registry gains an integrator the same way.
#include <memory>
#include <utility>

#include "integrators/make_integrator.hpp"

namespace structmd {

template <class B, class R>
struct IntegratorFactoryEntries {
    Registry<IntegratorFactory<B, R>> registry;

    template <template <class, class> class Kind, class Inputs>
    void integrator(ComponentKey key) {
        registry.add({std::move(key), [](const B& backend, const IntegratorScope& scope, const ParameterValues& v) {
                          return std::unique_ptr<Integrator<B, R>>(std::make_unique<Kind<B, R>>(backend, scope, v));
                      }});
    }
};

}  // namespace structmd
