#pragma once
// Engine's per-particle accessor (Simulation::read, write, read_of, write_of, view) and what loads
// and reshapes its particles (engine.hpp declares them).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "forcefield/magnetic_moment.hpp"
#include "simulation/engine.hpp"

namespace structmd {

namespace engine_detail {

inline constexpr double kIdentity[4] = {1.0, 0.0, 0.0, 0.0};

template <class R>
Real4<R> identity_quaternion() {
    return {R(1), R(0), R(0), R(0)};
}

// A host copy by slot, as doubles.
template <class T>
void copy_out(const std::vector<T>& values, double* out) {
    std::copy(values.begin(), values.end(), out);
}

template <class T, class R>
std::vector<R> as_reals(const std::vector<T>& values) {
    return std::vector<R>(values.begin(), values.end());
}

// Names the first force that is not finite, before a getter hands any over: one that fails leaves
// the caller's array alone.
inline void force_not_finite(int64_t id, int64_t step) {
    throw Error(STRUCTMD_ERR_NUMERICAL, "step " + std::to_string(step) + ", particle id " + std::to_string(id) +
                                            ": the force is not finite (overlapping particles?)");
}
inline void require_finite(const std::vector<double>& xyz, int64_t step) {
    for (size_t k = 0; k < xyz.size(); ++k)
        if (!std::isfinite(xyz[k])) force_not_finite(static_cast<int64_t>(k / 3), step);
}
template <class R>
void require_finite(const Real4<R>* values, const int64_t* ids, int64_t m, int64_t step) {
    for (int64_t k = 0; k < m; ++k)
        if (!std::isfinite(values[k].x) || !std::isfinite(values[k].y) || !std::isfinite(values[k].z))
            force_not_finite(ids[k], step);
}

}  // namespace engine_detail

template <class B, class R, class PairR>
void Engine<B, R, PairR>::load_particles(const SimulationSpec& spec) {
    using engine_detail::as_reals;
    p_.count = static_cast<int64_t>(spec.positions.size());
    p_.box = Box<R>::make(spec.box[0], spec.box[1], spec.box[2]);
    p_.noise = {spec.seed, spec.firstParticleId};
    io_.upload_positions(flatten(spec.positions).data(), boxLengths_, host_.typeIndex);
    io_.upload_velocities(spec.velocities.empty() ? maxwell_boltzmann(spec).data() : flatten(spec.velocities).data(),
                          host_.masses);
    backend_.resize(p_.force, p_.count);
    backend_.resize(p_.fault, 1);
    backend_.fill(p_.fault, kNoFault);
    set_clock(spec.currentStep, spec.simulationTime);
    const auto upload = [&](auto& buffer, const auto& values) {
        const auto reals = as_reals<typename std::decay_t<decltype(values)>::value_type, R>(values);
        backend_.upload(buffer, reals.data(), reals.size());
    };
    upload(p_.radius, spec.radius);
    upload(p_.charge, spec.charge);
    for_each_state_column([&](StateColumn c) { upload(p_.columns[c], spec.columns[c]); });
    // Orientations and torques only where the input has them or an integrator turns particles.
    const bool rotates = std::any_of(spec.integrators.begin(), spec.integrators.end(),
                                     [](const IntegratorSpec& s) { return s.rotates; });
    if (!spec.orientations.empty()) {
        std::vector<double> q;
        for (const auto& row : spec.orientations) q.insert(q.end(), row.begin(), row.end());
        io_.upload_orientations(q.data());
    } else if (rotates) {
        create_orientations();
    }
    if (rotates) backend_.resize(p_.torque, p_.count);
    if (!spec.magnetizations.empty()) {
        std::vector<Real4<R>> m;
        for (const auto& row : spec.magnetizations) m.push_back({R(row[0]), R(row[1]), R(row[2]), R(row[3])});
        backend_.upload(p_.magnetization, m.data(), m.size());
    }
    const std::vector<int>& batchId = host_.batchId;
    if (std::any_of(batchId.begin(), batchId.end(), [](int b) { return b != 0; })) {
        backend_.upload(p_.batch, batchId.data(), batchId.size());
        std::vector<int> ids = batchId;
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        std::vector<int> index(batchId.size());
        for (size_t i = 0; i < index.size(); ++i)
            index[i] = static_cast<int>(std::lower_bound(ids.begin(), ids.end(), batchId[i]) - ids.begin());
        backend_.upload(p_.batchIndex, index.data(), index.size());
        context_.batches = static_cast<int>(ids.size());
    }
    backend_.upload(p_.model, spec.modelId.data(), spec.modelId.size());
    backend_.resize(p_.lambda, 1);
    backend_.fill(p_.lambda, spec.lambda);
    lambda_ = spec.lambda;
    context_.ntypes = spec.typeNames.size();
    context_.particles = p_.count;
    context_.constants = spec.constants;
    context_.batch = p_.batchIndex.empty() ? nullptr : p_.batchIndex.data();
    context_.model = p_.model.data();
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::create_orientations() {
    backend_.resize(p_.dir, p_.count);
    backend_.fill(p_.dir, engine_detail::identity_quaternion<R>());
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::create_external_forces() {
    if (!p_.externalForce.empty()) return;
    backend_.resize(p_.externalForce, p_.count);
    backend_.fill(p_.externalForce, Real4<R>{R(0), R(0), R(0), R(0)});
}

// Current forces, and forces a drift kernel cleared to the old field, follow the change in place;
// stale ones take the new field when evaluated.
template <class B, class R, class PairR>
void Engine<B, R, PairR>::replace_external_forces(const int64_t* ids, const Real4<R>* values, int64_t m) {
    Real4<R>* force = cache_.holds_external_forces(p_.version) ? p_.force.data() : nullptr;
    backend_.for_each(m, ReplaceExternalForces<R>{ids, values, p_.externalForce.data(), force});
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::read(PerParticle q, double* out) {
    backend_.activate();
    switch (q) {
        case PerParticle::positions: io_.download_vectors(p_.pos, out); return;
        case PerParticle::unwrappedPositions: {
            io_.download_vectors(p_.pos, out);
            const std::vector<Image> images = io_.download(p_.image);
            for (int64_t i = 0; i < p_.count; ++i) {
                out[3 * i] += Box<double>::image_offset(images[i].x, boxLengths_[0]);
                out[3 * i + 1] += Box<double>::image_offset(images[i].y, boxLengths_[1]);
                out[3 * i + 2] += Box<double>::image_offset(images[i].z, boxLengths_[2]);
            }
            return;
        }
        case PerParticle::images: {
            const std::vector<Image> images = io_.download(p_.image);
            for (int64_t i = 0; i < p_.count; ++i) {
                out[3 * i] = images[i].x;
                out[3 * i + 1] = images[i].y;
                out[3 * i + 2] = images[i].z;
            }
            return;
        }
        case PerParticle::velocities: io_.download_vectors(p_.vel, out); return;
        case PerParticle::forces: {
            compute(kForces);
            std::vector<double> forces(static_cast<size_t>(3 * p_.count));
            io_.download_vectors(p_.force, forces.data());
            engine_detail::require_finite(forces, current_step());
            std::copy(forces.begin(), forces.end(), out);
            return;
        }
        case PerParticle::energies: {
            compute(kEnergy);
            engine_detail::copy_out(io_.download(p_.energy), out);
            return;
        }
        case PerParticle::masses: slot_copies_on_host(); engine_detail::copy_out(host_.masses, out); return;
        case PerParticle::types: slot_copies_on_host(); engine_detail::copy_out(host_.typeIndex, out); return;
        case PerParticle::radii: slot_copies_on_host(); engine_detail::copy_out(host_.radii, out); return;
        case PerParticle::orientations: {
            if (p_.dir.empty()) {
                for (int64_t i = 0; i < p_.count; ++i)
                    std::copy(engine_detail::kIdentity, engine_detail::kIdentity + 4, out + 4 * i);
                return;
            }
            const std::vector<Real4<R>> dir = io_.download(p_.dir);
            for (int64_t i = 0; i < p_.count; ++i) {
                const double row[4] = {dir[i].x, dir[i].y, dir[i].z, dir[i].w};
                std::copy(row, row + 4, out + 4 * i);
            }
            return;
        }
        case PerParticle::torques:
            if (p_.torque.empty()) {
                backend_.resize(p_.torque, p_.count);
                cache_.forces_changed();  // the forces at hand came without torques
            }
            compute(kForces);
            io_.download_vectors(p_.torque, out);
            return;
        case PerParticle::magneticMoments: {
            if (p_.magnetization.empty()) {
                std::fill(out, out + 3 * p_.count, 0.0);
                return;
            }
            const std::vector<Real4<R>> moments = io_.download(p_.magnetization);
            const std::vector<Real4<R>> dir = p_.dir.empty() ? std::vector<Real4<R>>() : io_.download(p_.dir);
            for (int64_t i = 0; i < p_.count; ++i) {
                const Vec3<R> mu = magnetic_moment(moments.data(), dir.empty() ? nullptr : dir.data(), i);
                out[3 * i] = mu.x;
                out[3 * i + 1] = mu.y;
                out[3 * i + 2] = mu.z;
            }
            return;
        }
        case PerParticle::pairVirials: {
            backend_.resize(p_.virial, p_.count);
            backend_.fill(p_.virial, zero_tensor<R>());
            ForceOutputs<R> outputs;
            outputs.virial = p_.virial.data();
            forceField_.compute_pairwise(p_, outputs);
            ForceCache<B, R>::count(outputs, evaluations_);
            cache_.virial_overwritten();
            const std::vector<Tensor3<R>> values = io_.download(p_.virial);
            for (int64_t i = 0; i < p_.count; ++i) {
                const Tensor3<R>& t = values[i];
                const R row[9] = {t.xx, t.xy, t.xz, t.yx, t.yy, t.yz, t.zx, t.zy, t.zz};
                std::copy(row, row + 9, out + 9 * i);
            }
            return;
        }
        case PerParticle::externalForces: break;
    }
    throw Error(STRUCTMD_ERR_INTERNAL, std::string("the ") + traits(q).name + " cannot be read");
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::write(PerParticle q, const double* in) {
    backend_.activate();
    switch (q) {
        case PerParticle::positions:
            io_.upload_positions(in, boxLengths_, host_.typeIndex);
            positions_changed();
            return;
        case PerParticle::velocities: io_.upload_velocities(in, host_.masses); return;
        case PerParticle::orientations:
            io_.upload_orientations(in);
            // Orientations place what terms attach to particles (patches): a new configuration.
            ++p_.version;
            cache_.invalidate();
            return;
        case PerParticle::externalForces:
            if (in == nullptr) {
                if (!p_.externalForce.empty()) replace_external_forces(nullptr, nullptr, p_.count);
                p_.externalForce.release();
                externalEnergy_ = 0.0;  // no field, no field energy
                return;
            }
            create_external_forces();
            replace_external_forces(nullptr, io_.pack_forces(in, p_.count), p_.count);
            io_.staged_read(p_.count);
            return;
        default: break;
    }
    throw Error(STRUCTMD_ERR_INTERNAL, std::string("the ") + traits(q).name + " cannot be written");
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::read_of(PerParticle q, const int64_t* ids, int64_t m, double* out) {
    backend_.activate();
    switch (q) {
        case PerParticle::positions: io_.watched_positions(ids, m, out); return;
        case PerParticle::velocities:
            io_.upload_ids(ids, m);
            unpack_vectors(io_.gather(p_.vel, m), m, out);
            return;
        case PerParticle::forces: {
            compute(kForces);
            io_.upload_ids(ids, m);
            const Real4<R>* values = io_.gather(p_.force, m);
            engine_detail::require_finite(values, ids, m, current_step());
            unpack_vectors(values, m, out);
            return;
        }
        default: break;
    }
    throw Error(STRUCTMD_ERR_INTERNAL, std::string("the ") + traits(q).name + " of a subset cannot be read");
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::write_of(PerParticle q, const int64_t* ids, int64_t m, const double* in) {
    backend_.activate();
    switch (q) {
        case PerParticle::positions:
            io_.scatter_positions(ids, m, in, boxLengths_, host_.typeIndex);
            positions_changed();
            return;
        case PerParticle::velocities: io_.scatter_velocities(ids, m, in, host_.masses); return;
        case PerParticle::externalForces:
            io_.pack_forces(in, m);
            io_.upload_ids(ids, m);
            create_external_forces();
            replace_external_forces(io_.uploaded_ids(), io_.staged_vectors(), m);
            io_.staged_read(m);
            return;
        default: break;
    }
    throw Error(STRUCTMD_ERR_INTERNAL, std::string("the ") + traits(q).name + " of a subset cannot be written");
}

template <class B, class R, class PairR>
Simulation::ArrayView Engine<B, R, PairR>::view(const std::string& quantity) {
    backend_.activate();
    const Real4<R>* data = nullptr;
    if (quantity == "positions") {
        data = p_.pos.data();
    } else if (quantity == "velocities") {
        data = p_.vel.data();
    } else if (quantity == "forces") {
        compute(kForces);
        // On the backend, so that a view of the forces stays a view.
        const double bad = backend_.reduce(p_.count, NonFiniteForce<R>{p_.force.data()}, 0.0);
        if (bad > 0)
            throw Error(STRUCTMD_ERR_NUMERICAL, "step " + std::to_string(current_step()) + ": the forces of " +
                                                    std::to_string(static_cast<int64_t>(bad)) +
                                                    " particles are not finite (overlapping particles?)");
        data = p_.force.data();
    } else {
        throw Error(STRUCTMD_ERR_ARGUMENT,
                    "quantity: '" + quantity + "' has no view (known: positions, velocities, forces)");
    }
    backend_.synchronize();
    return {data, p_.count, static_cast<int>(sizeof(R)), backend_.device_ordinal()};
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::set_box(const double lengths[3]) {
    backend_.activate();
    // 0 or infinity: an open axis, kept as infinity (core/box.hpp).
    double given[3];
    for (int d = 0; d < 3; ++d) {
        given[d] = lengths[d] == 0.0 ? kOpenAxis : lengths[d];
        if (!is_box_length(given[d]))
            throw Error(STRUCTMD_ERR_ARGUMENT, "lengths[" + std::to_string(d) + "]: expected a box length > 0 and "
                                               "<= 1e15, or 0 or infinity for an open axis, got " + precise(lengths[d]));
    }
    lengths = given;
    if (!cutoff_fits_box(largestCutoff_, {lengths[0], lengths[1], lengths[2]}))
        throw Error(STRUCTMD_ERR_ARGUMENT, "lengths: the largest cutoff (" + precise(largestCutoff_) +
                                               ") must be shorter than half the box (" +
                                               precise(half_shortest_edge(lengths[0], lengths[1], lengths[2])) + ")");
    std::vector<double> xyz(3 * p_.count);
    read(PerParticle::unwrappedPositions, xyz.data());
    // Fractional coordinates are kept along axes periodic before and after; along an axis open before
    // or after the positions stay where they are (an open axis has no fraction).
    for (int d = 0; d < 3; ++d) {
        if (is_open_axis(lengths[d]) || is_open_axis(boxLengths_[d])) continue;
        for (int64_t i = 0; i < p_.count; ++i) xyz[3 * i + d] *= lengths[d] / boxLengths_[d];
    }
    boxLengths_ = {lengths[0], lengths[1], lengths[2]};
    p_.box = Box<R>::make(lengths[0], lengths[1], lengths[2]);
    write(PerParticle::positions, xyz.data());
}

}  // namespace structmd
