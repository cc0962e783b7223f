#pragma once
// Makes an engine's integrators with the factories it is given: an IntegratorSpec names its
// integrator by key, and nothing here knows one by name.
#include <functional>
#include <memory>

#include "core/error.hpp"
#include "core/registry.hpp"
#include "core/logger.hpp"
#include "integrators/integrator.hpp"
#include "integrators/integrator_spec.hpp"

namespace structmd {

template <class B, class R>
struct IntegratorFactory {
    ComponentKey key;
    std::function<std::unique_ptr<Integrator<B, R>>(const B&, const IntegratorScope&, const ParameterValues&)> make;
};

// The built-in integrators' factories of engine type <B, R>, made once per process; defined in
// builtin_integrator_factories.hpp and built in a unit of their own per engine type (src/engines/).
template <class B, class R>
const Registry<IntegratorFactory<B, R>>& builtin_integrator_factories();

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
