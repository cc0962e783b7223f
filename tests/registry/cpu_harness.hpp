#pragma once
// Builds a force field from its spec with the engine's own factories (make_interactors) on the CPU
// backend in double precision, and evaluates it on the particles of the input, without an engine.
// The built-in factories are the CPU double engine's own, compiled in its units (structmd_engines),
// so the tests compile none of them again.
#include <memory>
#include <string>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "core/registry.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/make_interactors.hpp"
#include "input/description.hpp"

namespace structmd::registry_test {

using CpuFactories = Registry<InteractorFactory<CpuBackend, double>>;

// builtin_interactor_factories<CpuBackend, double, double>(): what the CPU double engine builds with.
const CpuFactories& cpu_factories();

// A document read as far as the force field (the parsed document is kept: the system refers to it).
struct Scene {
    std::shared_ptr<const input::ParsedDocument> parsed;
    ForceFieldSpec spec;
    const input::SystemDescription& system() const { return parsed->system; }
};

Scene read_scene(const std::string& text, const Registry<ForceFieldComponent>& registry = forcefield_registry());

// For each time: the total potential energy of the force field, the 3n force components and the 3n
// torque components (terms acting on orientations), with
// the particles where the input puts them (time matters to fields that move).
std::vector<double> evaluate(const Scene& scene, const ForceFieldSpec& spec, const std::vector<double>& times,
                             const CpuFactories& factories = cpu_factories());

}  // namespace structmd::registry_test
