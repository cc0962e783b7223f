#pragma once
// What an engine's interactor factories are given (make_interactors.hpp builds the force field
// with them): the backend, the engine data, the spec and the force field under construction.
// Configurable components (component_registry.hpp) write their factory against this alone.
#include <functional>
#include <memory>

#include "core/logger.hpp"
#include "core/registry.hpp"
#include "forcefield/force_field.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/pair_potential.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

// The engine-side data a force field is built against.
struct ForceFieldContext {
    size_t ntypes = 0;
    int64_t particles = 0;
    Constants constants;
    const int* batch = nullptr;  // backend arrays by particle, or null where not needed: batches
    int batches = 1;             // numbered 0 .. batches - 1, in the order of their batchId
    const int* model = nullptr;
    const Logger* log = nullptr;  // for what the build reports (a kernel's compile time)
    bool hessian = false;  // a measure asks for exact second derivatives: terms make their dual parameters
};

// What a factory is given: the backend, the engine data, and the force field under construction
// (its groups and the list a pair term runs over).
template <class B, class R>
struct InteractorBuild {
    const B& backend;
    const ForceFieldSpec& spec;
    const ForceFieldContext& context;
    ForceField<B, R>& forceField;
    std::function<std::shared_ptr<VerletList<B, R>>(const PairSpec&)> listFor;

    InteractorScope scope(const InteractionSpec& s) const {
        return InteractorScope{s.name, s.startStep, s.endStep, s.group >= 0 ? forceField.group(s.group) : nullptr};
    }
};

// One entry per component: makes the interactor of an InteractionSpec of the component's kind
// (a PairSpec, BondSpec or ExternalSpec).
template <class B, class R>
struct InteractorFactory {
    ComponentKey key;
    std::function<std::unique_ptr<Interactor<B, R>>(const InteractorBuild<B, R>&, const InteractionSpec&)> make;
};

}  // namespace structmd
