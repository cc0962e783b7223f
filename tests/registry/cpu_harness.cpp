#include "cpu_harness.hpp"

#include "core/logger.hpp"
#include "forcefield/builtin_factories.hpp"
#include "forcefield/make_interactors.hpp"
#include "forcefield/read_forcefield.hpp"
#include "state/fault.hpp"
#include "state/particles.hpp"

namespace structmd::registry_test {

const CpuFactories& cpu_factories() { return builtin_interactor_factories<CpuBackend, double, double>(); }

Scene read_scene(const std::string& text, const Registry<ForceFieldComponent>& registry) {
    Scene scene;
    scene.parsed = std::make_shared<const input::ParsedDocument>(input::parse_document(text));
    scene.spec = read_forcefield(scene.parsed->system, Logger(LogLevel::quiet, nullptr), registry);
    return scene;
}

std::vector<double> evaluate(const Scene& scene, const ForceFieldSpec& spec, const std::vector<double>& times,
                             const CpuFactories& factories) {
    const input::SystemDescription& system = scene.system();
    const int64_t n = system.numParticles();
    const CpuBackend backend(1);
    Particles<CpuBackend, double> p;
    // The ensemble's lambda, which the terms of lambda read where the engine keeps it.
    const double lambda = system.lambda.value_or(1.0);
    backend.upload(p.lambda, &lambda, 1);
    ForceFieldContext context;
    context.ntypes = system.types.size();
    context.particles = n;
    context.constants = constants_of(system);
    context.constants.lambda = p.lambda.data();
    ForceField<CpuBackend, double> forceField = make_interactors<CpuBackend, double>(backend, spec, context, factories);

    p.count = n;
    p.box = Box<double>::make(system.box[0], system.box[1], system.box[2]);
    std::vector<Real4<double>> pos;
    for (int64_t i = 0; i < n; ++i)
        pos.push_back({system.positions[i][0], system.positions[i][1], system.positions[i][2],
                       static_cast<double>(system.typeIndex[i])});
    backend.upload(p.pos, pos.data(), pos.size());
    backend.upload(p.radius, system.radius.data(), system.radius.size());
    backend.upload(p.charge, system.charge.data(), system.charge.size());
    // At rest, with their masses (w), which the terms of masses (Gravity) read.
    std::vector<Real4<double>> velocities;
    for (double m : system.mass) velocities.push_back({0, 0, 0, m});
    backend.upload(p.vel, velocities.data(), velocities.size());
    // The magnetic moments, which the magnetic terms read (the minimal inputs give every particle one).
    std::vector<Real4<double>> moments;
    for (const auto& m : system.magnetizations) moments.push_back({m[0], m[1], m[2], m[3]});
    backend.upload(p.magnetization, moments.data(), moments.size());
    const unsigned long long noFault = kNoFault;
    backend.upload(p.fault, &noFault, 1);
    backend.resize(p.force, n);
    backend.resize(p.energy, n);
    backend.resize(p.torque, n);
    p.version = 1;

    std::vector<double> result;
    for (double time : times) {
        // Step 0 at `time`, on the host and on the backend's clock alike.
        p.timeline.reset(0, time);
        const StepClock clock{0, time};
        backend.upload(p.clock, &clock, 1);
        backend.fill(p.force, Real4<double>{0, 0, 0, 0});
        backend.fill(p.energy, 0.0);
        backend.fill(p.torque, Real4<double>{0, 0, 0, 0});
        forceField.prepare(p);
        forceField.compute_all(p, ForceOutputs<double>{p.force.data(), p.energy.data(), nullptr, p.torque.data()});
        double energy = 0.0;
        for (int64_t i = 0; i < n; ++i) energy += p.energy.data()[i];
        result.push_back(energy);
        for (int64_t i = 0; i < n; ++i) {
            const Real4<double>& f = p.force.data()[i];
            result.insert(result.end(), {f.x, f.y, f.z});
        }
        for (int64_t i = 0; i < n; ++i) {
            const Real4<double>& t = p.torque.data()[i];
            result.insert(result.end(), {t.x, t.y, t.z});
        }
    }
    return result;
}

}  // namespace structmd::registry_test
