#pragma once
// Each engine's integrator factories, made once per engine type from the built-in list
// (integrators.hpp): an IntegratorSpec names its integrator by key, and nothing here knows one by name.
#include <functional>
#include <memory>

#include "core/error.hpp"
#include "core/registry.hpp"
#include "integrators/integrator_spec.hpp"
#include "integrators/integrators.hpp"

namespace structmd {

template <class B, class R>
struct IntegratorFactory {
    ComponentKey key;
    std::function<std::unique_ptr<Integrator<B, R>>(const B&, const IntegratorScope&, const ParameterValues&)> make;
};

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

template <class B, class R>
const Registry<IntegratorFactory<B, R>>& builtin_integrator_factories() {
    static const Registry<IntegratorFactory<B, R>> builtin = [] {
        IntegratorFactoryEntries<B, R> entries;
        visit_builtin_integrators(entries);
        return std::move(entries.registry);
    }();
    return builtin;
}

template <class B, class R>
std::unique_ptr<Integrator<B, R>> make_integrator(const B& backend, const IntegratorSpec& spec, const uint8_t* group,
                                                  const Registry<IntegratorFactory<B, R>>& factories,
                                                  const Logger* log = nullptr) {
    const IntegratorFactory<B, R>* factory = factories.find(spec.key);
    if (!factory) throw Error(STRUCTMD_ERR_INTERNAL, spec.path + ": " + spec.key.text() + " has no implementation");
    return factory->make(backend, IntegratorScope{spec.timeStep, spec.temperature, group, spec.name, log, spec.path},
                         spec.parameters);
}

}  // namespace structmd
