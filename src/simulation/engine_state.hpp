#pragma once
// Engine's state as a whole: its energies and virial, checkpoints (state_checkpoint.hpp for the
// layout) and a change of parameters, which makes the force field and the integrators again around
// the same particles.
#include <string>
#include <vector>

#include "simulation/checkpoint_file.hpp"
#include "simulation/engine.hpp"
#include "simulation/state_checkpoint.hpp"

namespace structmd {

template <class B, class R, class PairR>
double Engine<B, R, PairR>::energy(const std::string& request) {
    backend_.activate();
    const EnergyRequest r = parse_energy_request(request, host_.batchId, forceField_.names());
    if (r.host) return externalEnergy_;
    if (r.callback) {
        callbacks_.evaluate(backend_, p_);
        return callbacks_.empty() ? 0.0 : callbacks_.energy();
    }
    refresh_ghosts();
    if (r.term == "kinetic") return kinetic_energy(r.batch);
    if (r.term == "potential") return potential_energy(r.batch);
    // The host's field belongs to no batch: it is part of the whole system's total only.
    if (r.term == "total")
        return kinetic_energy(r.batch) + potential_energy(r.batch) + (r.batch < 0 ? externalEnergy_ : 0.0);
    backend_.resize(p_.energy, p_.count);
    backend_.fill(p_.energy, R(0));
    const ForceOutputs<R> out = energy_outputs(p_.energy.data());
    forceField_.compute_one(forceField_.find(r.term), p_, out);
    ForceCache<B, R>::count(out, evaluations_);
    cache_.energy_overwritten();
    return sum_energy(r.batch);
}

template <class B, class R, class PairR>
std::array<double, 9> Engine<B, R, PairR>::virial() {
    compute(kVirial);
    const Tensor3<double> w = backend_.reduce(p_.count, SumVirial<R>{p_.virial.data()}, zero_tensor<double>());
    std::array<double, 9> total{w.xx, w.xy, w.xz, w.yx, w.yy, w.yz, w.zx, w.zy, w.zz};
    if (!callbacks_.empty())
        for (int k = 0; k < 9; ++k) total[k] += callbacks_.virial()[k];
    return total;
}

template <class B, class R, class PairR>
double Engine<B, R, PairR>::sum_energy(int batch) {
    if (batch < 0) return backend_.reduce(p_.count, SumEnergy<R>{p_.energy.data()}, 0.0);
    return backend_.reduce(p_.count, InBatch<SumEnergy<R>>{{p_.energy.data()}, p_.batch.data(), batch}, 0.0);
}

// The callbacks' energy belongs to no batch: it is part of the whole system's potential only.
template <class B, class R, class PairR>
double Engine<B, R, PairR>::potential_energy(int batch) {
    cache_.evaluate(kEnergy, backend_, p_, forceField_, callbacks_, evaluations_);
    return sum_energy(batch) + (batch < 0 && !callbacks_.empty() ? callbacks_.energy() : 0.0);
}

template <class B, class R, class PairR>
double Engine<B, R, PairR>::kinetic_energy(int batch) {
    if (batch < 0) return backend_.reduce(p_.count, KineticEnergy<R>{p_.vel.data()}, 0.0);
    return backend_.reduce(p_.count, InBatch<KineticEnergy<R>>{{p_.vel.data()}, p_.batch.data(), batch}, 0.0);
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::change_parameters(const RuntimeSpec& spec, const ForceFieldComponents& components) {
    backend_.activate();
    if (spec.integrators.size() != integrators_.size())
        throw Error(STRUCTMD_ERR_INTERNAL, "a parameter change altered the list of integrators");
    const double cutoff = spec.forceField.largest_cutoff();
    if (!cutoff_fits_box(cutoff, boxLengths_))
        throw Error(STRUCTMD_ERR_ARGUMENT,
                    "the largest cutoff (" + precise(cutoff) + ") must be shorter than half the box (" +
                        precise(half_shortest_edge(boxLengths_[0], boxLengths_[1], boxLengths_[2])) + ")");
    // Built beside the present ones: a failure (a kernel that does not compile, memory) changes nothing.
    // The new constants (a new temperature, which a term in units of k_B T scales with) are in the
    // context the force field is made with; a failure puts the old ones back.
    const Constants previousConstants = context_.constants;
    context_.constants = spec.constants;
    context_.constants.lambda = p_.lambda.data();
    ForceField<B, R> forceField;
    std::vector<std::unique_ptr<Integrator<B, R>>> integrators;
    try {
        forceField = make_force_field(spec.forceField, components, &forceField_);
        integrators = make_integrators(spec.integrators, forceField);
        for (size_t k = 0; k < integrators.size(); ++k) integrators[k]->restore(integrators_[k]->state());
    } catch (...) {
        context_.constants = previousConstants;
        throw;
    }
    forceField_.adapt();
    retiredListBuilds_ += forceField_.builds();
    forceField_ = std::move(forceField);
    integrators_ = std::move(integrators);
    largestCutoff_ = cutoff;
    limit_moves();
    cache_.invalidate();  // forces, energies and virial change with the parameters; the lists are new
    backend_.synchronize();
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::save_checkpoint(const std::string& path) {
    backend_.activate();
    DynamicState<R> s;
    s.firstStep = schedule_.first_step();
    s.step = current_step();
    s.time = current_time();
    s.activeStage = activeStage_;
    s.box = boxLengths_;
    s.lambda = lambda_;
    s.pos = io_.download(p_.pos);
    s.image = io_.download(p_.image);
    s.vel = io_.download(p_.vel);
    if (!p_.externalForce.empty()) s.externalForce = io_.download(p_.externalForce);
    if (!p_.dir.empty()) s.dir = io_.download(p_.dir);
    if (!p_.magnetization.empty()) s.magnetization = io_.download(p_.magnetization);
    for (const auto& integrator : integrators_) s.integrators.push_back(integrator->state());
    write_checkpoint_file(path, encode_state(s));
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::load_checkpoint(const std::string& path) {
    const StateShape shape{precision_label<R, PairR>(),
                           p_.count,
                           schedule_.first_step(),
                           final_step(),
                           schedule_.stages(),
                           integrators_.size(),
                           static_cast<int>(host_.typeNames.size()),
                           largestCutoff_};
    const DynamicState<R> s = decode_state<R>(read_checkpoint_file(path), path, shape);
    // Everything read and checked: now the state changes.
    backend_.activate();
    boxLengths_ = s.box;
    p_.box = Box<R>::make(s.box[0], s.box[1], s.box[2]);
    backend_.upload(p_.pos, s.pos.data(), s.pos.size());
    backend_.upload(p_.image, s.image.data(), s.image.size());
    backend_.upload(p_.vel, s.vel.data(), s.vel.size());
    if (s.externalForce.empty())
        p_.externalForce.release();
    else
        backend_.upload(p_.externalForce, s.externalForce.data(), s.externalForce.size());
    // A state saved without orientations had every particle at the identity.
    if (!s.dir.empty())
        backend_.upload(p_.dir, s.dir.data(), s.dir.size());
    else if (!p_.dir.empty())
        backend_.fill(p_.dir, engine_detail::identity_quaternion<R>());
    if (!s.magnetization.empty() && !p_.magnetization.empty())
        backend_.upload(p_.magnetization, s.magnetization.data(), s.magnetization.size());
    for (size_t k = 0; k < integrators_.size(); ++k) integrators_[k]->restore(s.integrators[k]);
    set_lambda(s.lambda);
    activeStage_ = s.activeStage;
    set_clock(s.step, s.time);
    positions_changed();
}

}  // namespace structmd
