#pragma once
// Engine<Backend, Real>: particles, force field, integrators and simulation steps on one backend in
// one precision, and the step loop. Its parts live beside it: what is current (force_cache.hpp),
// the state a call can roll back to (rollback.hpp), checkpoints (state_checkpoint.hpp), energy
// terms (energy_terms.hpp), host packing (host_transfer.hpp) and the schedule (schedule.hpp); the
// step and time have one owner, the particles' Timeline.
#include <algorithm>
#include <optional>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/logger.hpp"
#include "forcefield/component_set.hpp"
#include "forcefield/magnetic_moment.hpp"
#include "forcefield/builtin_factories.hpp"
#include "forcefield/make_interactors.hpp"
#include "integrators/make_integrator.hpp"
#include "simulation/callback_term.hpp"
#include "simulation/domain_slots.hpp"
#include "simulation/checkpoint_file.hpp"
#include "simulation/energy_terms.hpp"
#include "simulation/engine_functors.hpp"
#include "simulation/fault_report.hpp"
#include "simulation/force_cache.hpp"
#include "simulation/host_transfer.hpp"
#include "simulation/read_simulation.hpp"
#include "simulation/rollback.hpp"
#include "simulation/schedule.hpp"
#include "simulation/simulation.hpp"
#include "simulation/simulation_spec.hpp"
#include "simulation/state_checkpoint.hpp"

namespace structmd {

// R: positions, velocities, forces and sums; PairR: the arithmetic of non-bonded pair terms.
template <class R, class PairR>
constexpr const char* precision_label() {
    if constexpr (sizeof(R) == sizeof(PairR)) return sizeof(R) == sizeof(float) ? "single" : "double";
    return "mixed";
}

template <class B, class R, class PairR = R>
class Engine final : public Simulation, private ForceSource {
public:
    // `components`: the handle's force-field components (built-ins and its plugins'), whose
    // factories build the force field.
    template <class... BackendArgs>
    Engine(SimulationSpec spec, const ForceFieldComponents& components, const Logger& log, BackendArgs&&... backendArgs)
        : backend_(std::forward<BackendArgs>(backendArgs)...),
          log_(log),
          schedule_(spec.currentStep, spec.schedule),
          steps_(std::move(spec.steps)),
          typeIndex_(spec.typeIndex),
          batchId_(spec.batchId),
          masses_(spec.mass),
          radii_(spec.radius),
          typeNames_(spec.typeNames),
          boxLengths_(spec.box),
          boltzmann_(spec.constants.boltzmann),
          largestCutoff_(spec.forceField.largest_cutoff()) {
        backend_.activate();
        p_.count = static_cast<int64_t>(spec.positions.size());
        p_.box = Box<R>::make(spec.box[0], spec.box[1], spec.box[2]);
        p_.noise = {spec.seed, spec.firstParticleId};
        upload_positions(flatten(spec.positions).data());
        upload_velocities(spec.velocities.empty() ? maxwell_boltzmann(spec).data() : flatten(spec.velocities).data());
        backend_.resize(p_.force, p_.count);
        backend_.resize(p_.fault, 1);
        backend_.fill(p_.fault, kNoFault);
        set_clock(spec.currentStep, spec.simulationTime);
        const std::vector<R> radius(spec.radius.begin(), spec.radius.end());
        const std::vector<R> charge(spec.charge.begin(), spec.charge.end());
        backend_.upload(p_.radius, radius.data(), radius.size());
        backend_.upload(p_.charge, charge.data(), charge.size());
        const std::vector<R> friction(spec.friction.begin(), spec.friction.end());
        const std::vector<R> selfDiffusion(spec.selfDiffusion.begin(), spec.selfDiffusion.end());
        backend_.upload(p_.friction, friction.data(), friction.size());
        backend_.upload(p_.selfDiffusion, selfDiffusion.data(), selfDiffusion.size());
        const std::vector<R> rotationalDiffusion(spec.rotationalSelfDiffusion.begin(), spec.rotationalSelfDiffusion.end());
        backend_.upload(p_.rotationalSelfDiffusion, rotationalDiffusion.data(), rotationalDiffusion.size());
        // Orientations and torques only where the input has them or an integrator turns particles.
        const bool rotates = std::any_of(spec.integrators.begin(), spec.integrators.end(),
                                         [](const IntegratorSpec& s) { return s.rotates; });
        if (!spec.orientations.empty()) {
            std::vector<double> q;
            for (const auto& row : spec.orientations) q.insert(q.end(), row.begin(), row.end());
            upload_orientations(q.data());
        } else if (rotates) {
            create_orientations();
        }
        if (rotates) backend_.resize(p_.torque, p_.count);
        if (!spec.magnetizations.empty()) {
            std::vector<Real4<R>> m;
            for (const auto& row : spec.magnetizations) m.push_back({R(row[0]), R(row[1]), R(row[2]), R(row[3])});
            backend_.upload(p_.magnetization, m.data(), m.size());
        }
        const std::vector<R> anisotropy(spec.anisotropy.begin(), spec.anisotropy.end());
        backend_.upload(p_.anisotropy, anisotropy.data(), anisotropy.size());
        if (std::any_of(batchId_.begin(), batchId_.end(), [](int b) { return b != 0; })) {
            backend_.upload(p_.batch, batchId_.data(), batchId_.size());
            std::vector<int> ids = batchId_;
            std::sort(ids.begin(), ids.end());
            ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
            std::vector<int> index(batchId_.size());
            for (size_t i = 0; i < index.size(); ++i)
                index[i] = static_cast<int>(std::lower_bound(ids.begin(), ids.end(), batchId_[i]) - ids.begin());
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
        context_.constants.lambda = p_.lambda.data();
        context_.batch = p_.batchIndex.empty() ? nullptr : p_.batchIndex.data();
        context_.model = p_.model.data();
        context_.log = &log_;
        const auto hessianStep = std::find_if(steps_.begin(), steps_.end(), [](const auto& s) { return s->needs_hessian(); });
        context_.hessian = hessianStep != steps_.end();
        forceField_ = make_force_field(spec.forceField, components, nullptr);
        const auto pairForceStep = std::find_if(steps_.begin(), steps_.end(), [](const auto& s) { return s->needs_pair_forces(); });
        pairForces_ = pairForceStep != steps_.end();
        if (const std::string term = forceField_.term_without_pair_forces(); pairForces_ && !term.empty())
            throw Error(STRUCTMD_ERR_UNSUPPORTED,
                        "simulationStep." + (*pairForceStep)->name() + ".parameters.mode: \"Pairwise_force\" splits the "
                        "forces of every term between pairs, and forceField entry '" + term +
                        "' (an expression, a table, a plugin, a Set or an AFM term) cannot; \"Total_force\" works with every term");
        if (const std::string term = forceField_.term_without_hessian(); context_.hessian && !term.empty())
            throw Error(STRUCTMD_ERR_UNSUPPORTED,
                        "simulationStep." + (*hessianStep)->name() + ".parameters.mode: \"Analytical\" needs the second "
                        "derivatives of every term, and forceField entry '" + term +
                        "' (an expression, a table, a plugin, a torque on a set or an AFM tip) has none; \"Numerical\" "
                        "differentiates its forces instead");
        integrators_ = make_integrators(spec.integrators, forceField_);
        const double skin = forceField_.smallest_skin();
        p_.maxMove2 = std::isfinite(skin) ? skin * skin : 1e300;
        backend_.synchronize();
    }

    int64_t particle_count() const override { return p_.count; }
    int64_t massive_count() const override {
        slot_copies_on_host();
        return std::count_if(masses_.begin(), masses_.end(), [](double m) { return m > 0.0; });
    }
    int64_t current_step() const override { return p_.timeline.step(); }
    double current_time() const override { return p_.timeline.time(); }
    double boltzmann() const override { return boltzmann_; }
    std::array<double, 3> box() const override { return boxLengths_; }
    double volume() const override { return boxLengths_[0] * boxLengths_[1] * boxLengths_[2]; }
    int64_t final_step() const override { return schedule_.final_step(); }
    std::optional<double> overdamped_kT() const override {
        if (schedule_.stages() == 0) return std::nullopt;
        const Integrator<B, R>& next = *integrators_[schedule_.integrator_of(schedule_.stage_after(current_step()))];
        if (!next.overdamped()) return std::nullopt;
        return next.thermal_energy();
    }

    void advance(int64_t n) override {
        if (n < 0) throw Error(STRUCTMD_ERR_ARGUMENT, "nsteps: expected a count >= 0, got " + std::to_string(n));
        if (n > std::numeric_limits<int64_t>::max() - current_step())
            throw Error(STRUCTMD_ERR_ARGUMENT, "nsteps: " + std::to_string(n) + " steps from step " +
                                                   std::to_string(current_step()) + " would overflow the step counter");
        const int64_t last = final_step();
        if (n == 0) return;
        if (schedule_.stages() == 0)
            throw Error(STRUCTMD_ERR_STATE, "nothing integrates: the input has no integrator section, or its "
                                            "schedule lists no integrator (energies and forces can still be read)");
        backend_.activate();
        rollback_.save(backend_, p_, activeStage_, integrators_);
        lambdaAtCallStart_ = lambda_;
        stoppedBy_.clear();
        backend_.begin_steps();
        try {
            for (int64_t k = 0; k < n; ++k) {
                backend_.begin_step();
                fire_steps(current_step() == last);  // the schedule's final state, passed through
                if (!stoppedBy_.empty()) break;
                const int stage = schedule_.stage_after(current_step());
                Integrator<B, R>& integrator = *integrators_[schedule_.integrator_of(stage)];
                if (stage != activeStage_) {
                    integrator.begin(p_, *this);
                    activeStage_ = stage;
                }
                integrator.step(p_, *this);
                backend_.for_each(1, AdvanceClock{p_.clock.data(), integrator.time_advance()});
                p_.timeline.commit(integrator.time_advance());
            }
        } catch (const Error& e) {
            backend_.end_steps();
            // A host callback that fails stops the call as a blow-up does: back to its start.
            if (e.status() == STRUCTMD_ERR_CALLBACK) roll_back();
            throw;
        } catch (...) {
            backend_.end_steps();
            throw;
        }
        backend_.end_steps();
        check_fault(gather_watched_positions());
        if (current_step() == last) fire_steps(true);
        forceField_.adapt();
    }

    void request_stop(const std::string& by) override {
        if (stoppedBy_.empty()) stoppedBy_ = by;
    }
    const std::string& stopped_by() const override { return stoppedBy_; }
    void set_step_firing(StepFiring* firing) override { stepFiring_ = firing; }

    void take_steps(std::vector<std::unique_ptr<SimulationStep>>& into) override {
        for (auto& step : steps_) into.push_back(std::move(step));
        steps_.clear();
    }
    double list_radius() const override { return forceField_.largest_list_radius(); }
    double pair_cutoff() const override { return largestCutoff_; }
    void hold_ghosts(const DomainLayout& layout, GhostExchange* exchange, bool begun) override {
        backend_.activate();
        domain_.hold(p_, layout, exchange);
        p_.noise.ids = domain_.global_ids();
        ghostsAt_ = p_.version;  // the ghosts were loaded with their owners' present positions
        if (begun && schedule_.stages() > 0) activeStage_ = schedule_.stage_after(current_step());
        cache_.invalidate();
    }

    double largest_owned_move() override {
        backend_.activate();
        return std::sqrt(domain_.largest_owned_move(p_));
    }

    SlabSort sort_owned(const SlabGeometry& geometry) override {
        backend_.activate();
        return domain_.sort_owned(p_, geometry);
    }
    std::vector<std::vector<int64_t>> place_owned(const std::vector<Migrant>& arrivals,
                                                  const SlotAttributes& attributes) override {
        backend_.activate();
        return domain_.place_owned(arrivals, attributes, p_);
    }
    void place_ghosts(const std::vector<int64_t>& ghostIds, const SlotAttributes& attributes,
                      const DomainTerms& terms) override {
        backend_.activate();
        const int* model = p_.model.data();
        domain_.place_ghosts(p_, ghostIds, attributes);
        p_.noise.ids = domain_.global_ids();
        p_.drift = {};
        context_.particles = p_.count;
        context_.model = p_.model.data();
        // The host's copies by slot are not kept for a domain's slots: its view answers for them.
        typeIndex_.clear();
        masses_.clear();
        radii_.clear();
        batchId_.assign(static_cast<size_t>(p_.count), 0);
        // The terms read the particles' arrays where they are when they run, and their lists lay
        // themselves out again for the new count; only a list's filter holds an array's address
        // (the models'), so the force field is made again, its lists as large as they had grown,
        // only when that array moved. The integrators are made again over the new slots.
        if (p_.model.data() != model) {
            ForceField<B, R> forceField = make_force_field(*terms.forceField, *terms.components, &forceField_);
            forceField.reserve_lists_like(forceField_);
            retiredListBuilds_ += forceField_.builds();
            forceField_ = std::move(forceField);
        }
        std::vector<std::unique_ptr<Integrator<B, R>>> integrators = make_integrators(*terms.integrators, forceField_);
        for (size_t k = 0; k < integrators.size(); ++k) integrators[k]->restore(integrators_[k]->state());
        integrators_ = std::move(integrators);
        // The slots were renumbered, not moved: the owned slots' forces, renumbered with them, stay
        // current if they were, so the next step of velocity Verlet evaluates forces (and builds the
        // lists) only once it has moved the particles. The ghost slots hold no positions yet:
        // refreshed before the next evaluation.
        ++p_.version;
        forceField_.invalidate_lists();
        cache_.renumbered(p_.version - 1, p_.version);
        ghostsAt_ = -1;
    }
    std::vector<int64_t> global_ids() override {
        backend_.activate();
        return domain_.ids_on_host(p_.count);
    }

    void compute(unsigned flags) override {
        backend_.activate();
        refresh_ghosts();
        cache_.evaluate(flags, backend_, p_, forceField_, callbacks_, evaluations_);
    }

    void get_positions(double* xyz) override { download_vectors(p_.pos, xyz); }
    void get_velocities(double* v) override { download_vectors(p_.vel, v); }
    void get_images(int32_t* images) override {
        backend_.activate();
        std::vector<Image> values(p_.count);
        backend_.download(p_.image, values.data(), values.size());
        for (int64_t i = 0; i < p_.count; ++i) {
            images[3 * i] = values[i].x;
            images[3 * i + 1] = values[i].y;
            images[3 * i + 2] = values[i].z;
        }
    }
    void get_unwrapped_positions(double* xyz) override {
        get_positions(xyz);
        std::vector<int32_t> images(3 * p_.count);
        get_images(images.data());
        for (int64_t k = 0; k < 3 * p_.count; ++k) xyz[k] += images[k] * boxLengths_[k % 3];
    }
    void get_radii(double* r) override {
        slot_copies_on_host();
        std::copy(radii_.begin(), radii_.end(), r);
    }
    void get_orientations(double* q) override {
        backend_.activate();
        if (p_.dir.empty()) {
            for (int64_t i = 0; i < p_.count; ++i) std::copy(kIdentity, kIdentity + 4, q + 4 * i);
            return;
        }
        const Real4<R>* values = backend_.download(p_.dir, hostVectors_, p_.dir.size());
        for (int64_t i = 0; i < p_.count; ++i) {
            const double row[4] = {values[i].x, values[i].y, values[i].z, values[i].w};
            std::copy(row, row + 4, q + 4 * i);
        }
    }
    // Terms that read orientations see the new ones: what was computed from the old is stale.
    void set_orientations(const double* q) override {
        backend_.activate();
        upload_orientations(q);
        // Orientations place what terms attach to particles (patches): a new configuration.
        ++p_.version;
        cache_.invalidate();
    }
    void get_magnetic_moments(double* m) override {
        backend_.activate();
        if (p_.magnetization.empty()) {
            std::fill(m, m + 3 * p_.count, 0.0);
            return;
        }
        const std::vector<Real4<R>> moments = download(p_.magnetization);
        const std::vector<Real4<R>> dir = p_.dir.empty() ? std::vector<Real4<R>>() : download(p_.dir);
        for (int64_t i = 0; i < p_.count; ++i) {
            const Vec3<R> mu = magnetic_moment(moments.data(), dir.empty() ? nullptr : dir.data(), i);
            m[3 * i] = mu.x;
            m[3 * i + 1] = mu.y;
            m[3 * i + 2] = mu.z;
        }
    }
    bool has_magnetization() const override { return !p_.magnetization.empty(); }
    void get_torques(double* t) override {
        backend_.activate();
        if (p_.torque.empty()) {
            backend_.resize(p_.torque, p_.count);
            cache_.forces_changed();  // the forces at hand came without torques
        }
        compute(kForces);
        download_vectors(p_.torque, t);
    }
    const std::vector<std::string>& type_names() const override { return typeNames_; }
    // A failed getter leaves the caller's array alone: the forces are checked before they are handed over.
    void get_forces(double* f) override {
        compute(kForces);
        std::vector<double> values(3 * p_.count);
        download_vectors(p_.force, values.data());
        for (int64_t k = 0; k < 3 * p_.count; ++k)
            if (!std::isfinite(values[k]))
                throw Error(STRUCTMD_ERR_NUMERICAL, "step " + std::to_string(current_step()) + ", particle id " +
                                                        std::to_string(k / 3) +
                                                        ": the force is not finite (overlapping particles?)");
        std::copy(values.begin(), values.end(), f);
    }
    void get_particle_energies(double* e) override {
        compute(kEnergy);
        std::vector<R> values(p_.count);
        backend_.download(p_.energy, values.data(), values.size());
        std::copy(values.begin(), values.end(), e);
    }
    void get_masses(double* m) override {
        slot_copies_on_host();
        std::copy(masses_.begin(), masses_.end(), m);
    }
    void get_types(int32_t* types) override {
        slot_copies_on_host();
        std::copy(typeIndex_.begin(), typeIndex_.end(), types);
    }

    double energy(const std::string& request) override {
        backend_.activate();
        const EnergyRequest r = parse_energy_request(request, batchId_, forceField_.names());
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
        ForceOutputs<R> out;
        out.energy = p_.energy.data();
        forceField_.compute_one(forceField_.find(r.term), p_, out);
        ForceCache<B, R>::count(out, evaluations_);
        cache_.energy_overwritten();
        return sum_energy(r.batch);
    }
    std::vector<std::string> energy_terms() const override { return forceField_.names(); }
    void term_energies_and_forces(const std::string& term, double* energies, double* forces,
                                  double* torques) override {
        const int index = forceField_.find(term);
        if (index < 0) throw Error(STRUCTMD_ERR_ARGUMENT, "no forceField entry named '" + term + "'");
        backend_.activate();
        refresh_ghosts();
        backend_.resize(probedEnergies_, p_.count);
        backend_.fill(probedEnergies_, R(0));
        backend_.resize(probedForces_, p_.count);
        backend_.fill(probedForces_, Real4<R>{R(0), R(0), R(0), R(0)});
        backend_.resize(probedTorques_, p_.count);
        backend_.fill(probedTorques_, Real4<R>{R(0), R(0), R(0), R(0)});
        ForceOutputs<R> out;
        out.energy = probedEnergies_.data();
        out.force = probedForces_.data();
        out.torque = probedTorques_.data();
        forceField_.compute_one(index, p_, out);
        ForceCache<B, R>::count(out, evaluations_);
        const std::vector<R> values = download(probedEnergies_);
        std::copy(values.begin(), values.end(), energies);
        download_vectors(probedForces_, forces);
        download_vectors(probedTorques_, torques);
    }

    std::array<double, 9> virial() override {
        compute(kVirial);
        const Tensor3<double> w = backend_.reduce(p_.count, SumVirial<R>{p_.virial.data()}, zero_tensor<double>());
        std::array<double, 9> total{w.xx, w.xy, w.xz, w.yx, w.yy, w.yz, w.zx, w.zy, w.zz};
        if (!callbacks_.empty())
            for (int k = 0; k < 9; ++k) total[k] += callbacks_.virial()[k];
        return total;
    }

    void get_pair_virials(double* w) override {
        backend_.activate();
        backend_.resize(p_.virial, p_.count);
        backend_.fill(p_.virial, zero_tensor<R>());
        ForceOutputs<R> out;
        out.virial = p_.virial.data();
        forceField_.compute_pairwise(p_, out);
        ForceCache<B, R>::count(out, evaluations_);
        cache_.virial_overwritten();
        std::vector<Tensor3<R>> values(p_.count);
        backend_.download(p_.virial, values.data(), values.size());
        for (int64_t i = 0; i < p_.count; ++i) {
            const Tensor3<R>& t = values[i];
            const R row[9] = {t.xx, t.xy, t.xz, t.yx, t.yy, t.yz, t.zx, t.zy, t.zz};
            std::copy(row, row + 9, w + 9 * i);
        }
    }

    void hessian_column(int64_t id, double* blocks) override {
        if (!context_.hessian) throw Error(STRUCTMD_ERR_STATE, "no step of this input asks for second derivatives");
        backend_.activate();
        backend_.resize(hessian_, p_.count);
        backend_.fill(hessian_, zero_tensor<R>());
        forceField_.add_hessian(p_, static_cast<int>(id), hessian_.data());
        const std::vector<Tensor3<R>> values = download(hessian_);
        for (int64_t j = 0; j < p_.count; ++j) {
            const Tensor3<R>& t = values[j];
            const R block[9] = {t.xx, t.xy, t.xz, t.yx, t.yy, t.yz, t.zx, t.zy, t.zz};
            std::copy(block, block + 9, blocks + 9 * j);
        }
    }

    void pair_forces_on(int64_t id, double* f) override {
        if (!pairForces_) throw Error(STRUCTMD_ERR_STATE, "no step of this input asks for pair forces");
        backend_.activate();
        backend_.resize(probedForces_, p_.count);
        backend_.fill(probedForces_, Real4<R>{R(0), R(0), R(0), R(0)});
        forceField_.add_pair_forces(p_, static_cast<int>(id), probedForces_.data());
        download_vectors(probedForces_, f);
    }

    // The particle is moved in the positions array and back; the version moves on each time, so
    // neither a cached force nor a list refresh of the moved positions outlives the call.
    void forces_with_displaced(int64_t id, const double displacement[3], double* f) override {
        backend_.activate();
        upload_ids(&id, 1);
        const Real4<R> original = *gather(p_.pos, subsetIds_, 1);
        const Vec3<R> moved = p_.box.wrap(Vec3<R>{R(original.x + displacement[0]), R(original.y + displacement[1]),
                                                  R(original.z + displacement[2])});
        const auto place = [&](const Real4<R>& value) {
            *hostVectors_.reserve(1) = value;
            scatter(hostVectors_, p_.pos, 1);
            ++p_.version;
        };
        place(Real4<R>{moved.x, moved.y, moved.z, original.w});
        backend_.resize(probedForces_, p_.count);
        backend_.fill(probedForces_, Real4<R>{R(0), R(0), R(0), R(0)});
        ForceOutputs<R> out;
        out.force = probedForces_.data();
        forceField_.prepare(p_);
        forceField_.compute_all(p_, out);
        ForceCache<B, R>::count(out, evaluations_);
        place(original);
        download_vectors(probedForces_, f);
    }

    void set_positions(const double* xyz) override {
        backend_.activate();
        upload_positions(xyz);
        positions_changed();
    }
    void set_velocities(const double* v) override {
        backend_.activate();
        upload_velocities(v);
    }
    void set_box(const double lengths[3]) override {
        backend_.activate();
        for (int d = 0; d < 3; ++d)
            if (!(lengths[d] > 0.0 && lengths[d] <= kLargestBoxLength))
                throw Error(STRUCTMD_ERR_ARGUMENT, "lengths[" + std::to_string(d) + "]: expected a box length > 0 and "
                                                   "<= 1e15, got " + precise(lengths[d]));
        if (!cutoff_fits_box(largestCutoff_, {lengths[0], lengths[1], lengths[2]}))
            throw Error(STRUCTMD_ERR_ARGUMENT, "lengths: the largest cutoff (" + precise(largestCutoff_) +
                                                   ") must be shorter than half the box (" +
                                                   precise(half_shortest_edge(lengths[0], lengths[1], lengths[2])) + ")");
        std::vector<double> xyz(3 * p_.count);
        get_unwrapped_positions(xyz.data());
        for (int64_t i = 0; i < p_.count; ++i)
            for (int d = 0; d < 3; ++d) xyz[3 * i + d] *= lengths[d] / boxLengths_[d];
        boxLengths_ = {lengths[0], lengths[1], lengths[2]};
        p_.box = Box<R>::make(lengths[0], lengths[1], lengths[2]);
        set_positions(xyz.data());
    }
    double lambda() const override { return lambda_; }
    void set_lambda(double lambda) override {
        if (!(lambda >= 0.0 && lambda <= 1.0))
            throw Error(STRUCTMD_ERR_ARGUMENT, "lambda: expected a value in [0, 1], got " + precise(lambda));
        if (lambda == lambda_) return;
        backend_.activate();
        backend_.fill(p_.lambda, lambda);
        lambda_ = lambda;
        // The forces, energies and virials of the terms of lambda change at the same positions.
        if (forceField_.couples_to_lambda()) cache_.invalidate();
    }
    double lambda_derivative() override {
        if (!forceField_.couples_to_lambda()) return 0.0;
        backend_.activate();
        backend_.resize(lambdaDerivatives_, p_.count);
        backend_.fill(lambdaDerivatives_, R(0));
        forceField_.add_lambda_derivative(p_, lambdaDerivatives_.data());
        return backend_.reduce(p_.count, SumEnergy<R>{lambdaDerivatives_.data()}, 0.0);
    }

    void set_external_forces(const double* f) override {
        backend_.activate();
        if (f == nullptr) {
            if (!p_.externalForce.empty()) replace_external_forces(nullptr, nullptr, p_.count);
            p_.externalForce.release();
            externalEnergy_ = 0.0;  // no field, no field energy
            return;
        }
        pack_forces(f, p_.count);
        create_external_forces();
        replace_external_forces(nullptr, hostVectors_.data(), p_.count);
        backend_.read_from_host(hostVectors_, static_cast<size_t>(p_.count));
    }

    void get_positions_of(const int64_t* ids, int64_t m, double* xyz) override {
        if (watching(ids, m) && watchedVersion_ == p_.version) {
            unpack_vectors(watchedPositions_.data(), m, xyz);  // gathered by the last step call
        } else {
            watch(ids, m);
            unpack_vectors(gather(p_.pos, watchedIdsOnBackend_, m), m, xyz);
        }
        watchedRead_ = true;
    }
    void get_velocities_of(const int64_t* ids, int64_t m, double* v) override {
        upload_ids(ids, m);
        unpack_vectors(gather(p_.vel, subsetIds_, m), m, v);
    }
    // As get_forces: the m forces are checked before any is handed over.
    void get_forces_of(const int64_t* ids, int64_t m, double* f) override {
        compute(kForces);
        upload_ids(ids, m);
        const Real4<R>* values = gather(p_.force, subsetIds_, m);
        for (int64_t k = 0; k < m; ++k)
            if (!std::isfinite(values[k].x) || !std::isfinite(values[k].y) || !std::isfinite(values[k].z))
                throw Error(STRUCTMD_ERR_NUMERICAL, "step " + std::to_string(current_step()) + ", particle id " +
                                                        std::to_string(ids[k]) +
                                                        ": the force is not finite (overlapping particles?)");
        unpack_vectors(values, m, f);
    }
    // As set_positions for those particles: wrapped, images counted from the positions given, and
    // everything computed from positions made stale.
    void set_positions_of(const int64_t* ids, int64_t m, const double* xyz) override {
        backend_.activate();
        pack_positions_of<R>(xyz, ids, m, boxLengths_, typeIndex_, hostVectors_.reserve(m), hostImages_.reserve(m));
        upload_ids(ids, m);
        scatter(hostVectors_, p_.pos, m);
        scatter(hostImages_, p_.image, m);
        positions_changed();
    }
    void set_velocities_of(const int64_t* ids, int64_t m, const double* v) override {
        backend_.activate();
        pack_velocities_of<R>(v, ids, m, masses_, hostVectors_.reserve(m));
        upload_ids(ids, m);
        scatter(hostVectors_, p_.vel, m);
    }
    void set_external_forces_of(const int64_t* ids, int64_t m, const double* f) override {
        backend_.activate();
        pack_forces(f, m);
        upload_ids(ids, m);
        create_external_forces();
        replace_external_forces(subsetIds_.data(), hostVectors_.data(), m);
        backend_.read_from_host(hostVectors_, static_cast<size_t>(m));
    }
    void set_external_energy(double energy) override { externalEnergy_ = energy; }

    void set_force_callback(HostForceCallback callback) override {
        callbacks_.set_host(std::move(callback));
        cache_.invalidate();
    }
    void set_device_force_callback(DeviceForceCallback callback) override {
        callbacks_.set_device(std::move(callback));
        cache_.invalidate();
    }

    ArrayView view(const std::string& quantity) override {
        backend_.activate();
        const Real4<R>* data = nullptr;
        if (quantity == "positions") {
            data = p_.pos.data();
        } else if (quantity == "velocities") {
            data = p_.vel.data();
        } else if (quantity == "forces") {
            compute(kForces);
            require_finite_forces();
            data = p_.force.data();
        } else {
            throw Error(STRUCTMD_ERR_ARGUMENT,
                        "quantity: '" + quantity + "' has no view (known: positions, velocities, forces)");
        }
        backend_.synchronize();
        return {data, p_.count, static_cast<int>(sizeof(R)), backend_.device_ordinal()};
    }
    double external_energy() const override { return externalEnergy_; }

    void change_parameters(const RuntimeSpec& spec, const ForceFieldComponents& components) override {
        backend_.activate();
        if (spec.integrators.size() != integrators_.size())
            throw Error(STRUCTMD_ERR_INTERNAL, "a parameter change altered the list of integrators");
        const double cutoff = spec.forceField.largest_cutoff();
        if (!cutoff_fits_box(cutoff, boxLengths_))
            throw Error(STRUCTMD_ERR_ARGUMENT, "the largest cutoff (" + precise(cutoff) +
                                                   ") must be shorter than half the box (" +
                                                   precise(half_shortest_edge(boxLengths_[0], boxLengths_[1],
                                                                              boxLengths_[2])) + ")");
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
        const double skin = forceField_.smallest_skin();
        p_.maxMove2 = std::isfinite(skin) ? skin * skin : 1e300;
        cache_.invalidate();  // forces, energies and virial change with the parameters; the lists are new
        backend_.synchronize();
    }

    void save_checkpoint(const std::string& path) override {
        backend_.activate();
        DynamicState<R> s;
        s.firstStep = schedule_.first_step();
        s.step = current_step();
        s.time = current_time();
        s.activeStage = activeStage_;
        s.box = boxLengths_;
        s.lambda = lambda_;
        s.pos = download(p_.pos);
        s.image = download(p_.image);
        s.vel = download(p_.vel);
        if (!p_.externalForce.empty()) s.externalForce = download(p_.externalForce);
        if (!p_.dir.empty()) s.dir = download(p_.dir);
        if (!p_.magnetization.empty()) s.magnetization = download(p_.magnetization);
        for (const auto& integrator : integrators_) s.integrators.push_back(integrator->state());
        write_checkpoint_file(path, encode_state(s));
    }

    void load_checkpoint(const std::string& path) override {
        const StateShape shape{precision_label<R, PairR>(), p_.count,         schedule_.first_step(),
                               final_step(),                schedule_.stages(), integrators_.size()};
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
            backend_.fill(p_.dir, identity_quaternion());
        if (!s.magnetization.empty() && !p_.magnetization.empty())
            backend_.upload(p_.magnetization, s.magnetization.data(), s.magnetization.size());
        for (size_t k = 0; k < integrators_.size(); ++k) integrators_[k]->restore(s.integrators[k]);
        set_lambda(s.lambda);
        activeStage_ = s.activeStage;
        set_clock(s.step, s.time);
        positions_changed();
    }

    Counters counters() override {
        backend_.activate();
        Counters c = evaluations_;
        c.hostToDeviceBytes = backend_.transfers().hostToDevice;
        c.deviceToHostBytes = backend_.transfers().deviceToHost;
        c.deviceMemoryBytes = backend_.memory_bytes();
        c.stepGraphsCaptured = backend_.graphs_captured();
        c.stepGraphsReplayed = backend_.graphs_replayed();
        forceField_.adapt();  // reads the lists' build counts (after the transfers were taken)
        c.neighbourListBuilds = static_cast<uint64_t>(retiredListBuilds_ + forceField_.builds());
        return c;
    }

    std::string backend_name() const override { return B::name; }
    std::string precision_name() const override { return precision_label<R, PairR>(); }
    std::string device_name() const override { return backend_.device_name(); }
    int threads() const override { return backend_.threads(); }

private:
    // groupsOf: the force field whose group buffers the new one shares (null at construction).
    ForceField<B, R> make_force_field(const ForceFieldSpec& spec, const ForceFieldComponents& components,
                                      const ForceField<B, R>* groupsOf) {
        return make_interactors<B, R>(backend_, spec, context_,
                                      components.factories<B, R, PairR>(builtin_interactor_factories<B, R, PairR>(),
                                                                        spec, precision_label<R, PairR>()),
                                      groupsOf);
    }
    std::vector<std::unique_ptr<Integrator<B, R>>> make_integrators(const std::vector<IntegratorSpec>& specs,
                                                                    const ForceField<B, R>& forceField) {
        std::vector<std::unique_ptr<Integrator<B, R>>> made;
        for (const IntegratorSpec& integrator : specs)
            made.push_back(make_integrator<B, R>(backend_, integrator,
                                                 integrator.group >= 0 ? forceField.group(integrator.group) : nullptr,
                                                 builtin_integrator_factories<B, R>(), &log_));
        return made;
    }

    // The timeline and the backend's clock at (step, time).
    void set_clock(int64_t step, double time) {
        p_.timeline.reset(step, time);
        backend_.upload(p_.clock, &p_.timeline.launched(), 1);
    }

    // New positions (or a new box): every cached quantity and every list is out of date.
    void positions_changed() {
        ++p_.version;
        cache_.invalidate();
        forceField_.invalidate_lists();
    }

    // ForceSource
    void update_forces() override {
        if (!cache_.forces_current(p_.version)) refresh_ghosts();
        cache_.evaluate(kForces, backend_, p_, forceField_, callbacks_, evaluations_);
        arm_drift();
    }
    double potential_energy() override { return potential_energy(-1); }
    void positions_moved(double elapsed, bool driftBookkept) override {
        ++p_.version;
        p_.timeline.positions_moved(elapsed);
        if (!driftBookkept) return;
        if (p_.drift.force) cache_.forces_cleared(p_.version);
        if (p_.drift.slotOf) forceField_.drift_mirrored(p_.version);
    }

    // A spatial domain's view answers for its slots' types, masses and radii once it renumbered them.
    void slot_copies_on_host() const {
        if (domain_.held() && static_cast<int64_t>(masses_.size()) != p_.count)
            throw Error(STRUCTMD_ERR_INTERNAL, "a spatial domain's engine keeps no host copy of its slots' attributes");
    }

    // A spatial domain's ghosts take their owners' positions whenever the positions moved since
    // they last did (collective: every rank's engine makes the same calls). Their own drift moved
    // them with incomplete forces; the new positions are a new version, so the lists check them
    // afresh.
    void refresh_ghosts() {
        if (!domain_.held() || ghostsAt_ == p_.version) return;
        domain_.refresh(p_, hostVectors_);
        ++p_.version;
        ghostsAt_ = p_.version;
    }

    // What the next drift kernel can take over (state/drift_bookkeeping.hpp): clearing the forces,
    // unless torques are kept (they are cleared with them), and the first list's position copy.
    void arm_drift() {
        DriftBookkeeping<R> drift;
        if (p_.torque.empty()) {
            drift.force = p_.force.data();
            drift.external = p_.externalForce.empty() ? nullptr : p_.externalForce.data();
        }
        forceField_.mirror_in_drift(drift, p_);
        p_.drift = drift;
    }
    // Never cached: the field changes with the moments, which the magnetic integrators turn between
    // force evaluations. Only the terms that make a field are evaluated.
    void update_magnetic_field() override {
        backend_.resize(p_.magneticField, p_.count);
        backend_.fill(p_.magneticField, Real4<R>{R(0), R(0), R(0), R(0)});
        ForceOutputs<R> out;
        out.magneticField = p_.magneticField.data();
        forceField_.compute_magnetic_field(p_, out);
    }
    void magnetization_changed() override { cache_.invalidate(); }

    // Reports a fault recorded on the backend during the last steps and returns to the state the
    // call started from. faultStaged: a kernel queued last copies the fault word into faultWord_.
    void check_fault(bool faultStaged = false) {
        unsigned long long word;
        if (faultStaged) {
            backend_.synchronize();
            word = *faultWord_.data();
        } else {
            word = backend_.read(p_.fault, 0);
        }
        if (word == kNoFault) return;
        const int64_t failedStep = current_step();
        roll_back();
        throw Error(STRUCTMD_ERR_NUMERICAL, describe_fault(word, std::sqrt(p_.maxMove2), failedStep, current_step()));
    }
    // The state the step call started from, with any fault the device recorded meanwhile forgotten.
    void roll_back() {
        backend_.fill(p_.fault, kNoFault);
        activeStage_ = rollback_.restore(backend_, p_, integrators_);
        set_lambda(lambdaAtCallStart_);
        set_clock(p_.timeline.step(), p_.timeline.time());
        positions_changed();
    }

    // On the backend, so that a view of the forces stays a view.
    void require_finite_forces() {
        const double bad = backend_.reduce(p_.count, NonFiniteForce<R>{p_.force.data()}, 0.0);
        if (bad > 0)
            throw Error(STRUCTMD_ERR_NUMERICAL, "step " + std::to_string(current_step()) + ": the forces of " +
                                                    std::to_string(static_cast<int64_t>(bad)) +
                                                    " particles are not finite (overlapping particles?)");
    }

    // batch < 0: all particles.
    double sum_energy(int batch) {
        if (batch < 0) return backend_.reduce(p_.count, SumEnergy<R>{p_.energy.data()}, 0.0);
        return backend_.reduce(p_.count, InBatch<SumEnergy<R>>{{p_.energy.data()}, p_.batch.data(), batch}, 0.0);
    }
    // The callbacks' energy belongs to no batch: it is part of the whole system's potential only.
    double potential_energy(int batch) {
        cache_.evaluate(kEnergy, backend_, p_, forceField_, callbacks_, evaluations_);
        return sum_energy(batch) + (batch < 0 && !callbacks_.empty() ? callbacks_.energy() : 0.0);
    }
    double kinetic_energy(int batch) {
        if (batch < 0) return backend_.reduce(p_.count, KineticEnergy<R>{p_.vel.data()}, 0.0);
        return backend_.reduce(p_.count, InBatch<KineticEnergy<R>>{{p_.vel.data()}, p_.batch.data(), batch}, 0.0);
    }

    // Simulation steps see the state before the step is taken; the final state of the schedule
    // is given to every step whose window holds it.
    void fire_steps(bool final) {
        dueSteps_.clear();
        for (auto& s : steps_)
            if (final ? s->in_window(current_step()) : s->due(current_step())) dueSteps_.push_back(s.get());
        if (dueSteps_.empty()) return;
        if (stepFiring_) {
            stepFiring_->fire(dueSteps_);
            return;
        }
        for (SimulationStep* s : dueSteps_) s->fire(*this);
    }

    // All the digits a double needs, so that two numbers that differ never print alike.
    static std::string precise(double x) {
        char text[32];
        std::snprintf(text, sizeof text, "%.17g", x);
        return text;
    }

    void upload_positions(const double* xyz) {
        const auto n = static_cast<size_t>(p_.count);
        pack_positions_of<R>(xyz, nullptr, p_.count, boxLengths_, typeIndex_, hostVectors_.reserve(n),
                             hostImages_.reserve(n));
        backend_.upload(p_.pos, hostVectors_, n);
        backend_.upload(p_.image, hostImages_, n);
    }

    void upload_velocities(const double* v) {
        const auto n = static_cast<size_t>(p_.count);
        pack_velocities_of<R>(v, nullptr, p_.count, masses_, hostVectors_.reserve(n));
        backend_.upload(p_.vel, hostVectors_, n);
    }

    static constexpr double kIdentity[4] = {1.0, 0.0, 0.0, 0.0};
    static Real4<R> identity_quaternion() { return {R(1), R(0), R(0), R(0)}; }
    void create_orientations() {
        backend_.resize(p_.dir, p_.count);
        backend_.fill(p_.dir, identity_quaternion());
    }
    // n quaternions [q0, q1, q2, q3] into the orientations, which are made if there were none.
    void upload_orientations(const double* q) {
        const auto n = static_cast<size_t>(p_.count);
        Real4<R>* values = hostVectors_.reserve(n);
        for (size_t i = 0; i < n; ++i) values[i] = {R(q[4 * i]), R(q[4 * i + 1]), R(q[4 * i + 2]), R(q[4 * i + 3])};
        backend_.upload(p_.dir, hostVectors_, n);
    }

    // The m forces f (3m values) into the vector staging, as Real4 with w = 0.
    void pack_forces(const double* f, int64_t m) {
        Real4<R>* values = hostVectors_.reserve(static_cast<size_t>(m));
        for (int64_t k = 0; k < m; ++k) values[k] = {R(f[3 * k]), R(f[3 * k + 1]), R(f[3 * k + 2]), R(0)};
    }

    template <class T>
    std::vector<T> download(const typename B::template Buffer<T>& buffer) {
        std::vector<T> values(buffer.size());
        backend_.download(buffer, values.data(), values.size());
        return values;
    }

    void download_vectors(const typename B::template Buffer<Real4<R>>& buffer, double* out) {
        backend_.activate();
        unpack_vectors(backend_.download(buffer, hostVectors_, buffer.size()), static_cast<int64_t>(buffer.size()), out);
    }

    // The host's field, zero until it sets one.
    void create_external_forces() {
        if (!p_.externalForce.empty()) return;
        backend_.resize(p_.externalForce, p_.count);
        backend_.fill(p_.externalForce, Real4<R>{R(0), R(0), R(0), R(0)});
    }
    // Current forces, and forces a drift kernel cleared to the old field, follow the change in place;
    // stale ones take the new field when evaluated.
    void replace_external_forces(const int64_t* ids, const Real4<R>* values, int64_t m) {
        Real4<R>* force = cache_.holds_external_forces(p_.version) ? p_.force.data() : nullptr;
        backend_.for_each(m, ReplaceExternalForces<R>{ids, values, p_.externalForce.data(), force});
    }

    // Subsets by id (m > 0): a backend loop gathers the m entries into the host staging or scatters
    // them from it, directly (pinned memory on CUDA): one launch, no copy. The ids live on the backend.
    // A coupling loop names the same region call after call: those ids are on the backend already.
    void upload_ids(const int64_t* ids, int64_t m) {
        backend_.activate();
        if (uploadedIds_.size() == static_cast<size_t>(m) && std::equal(ids, ids + m, uploadedIds_.begin())) return;
        std::copy(ids, ids + m, hostIds_.reserve(static_cast<size_t>(m)));
        backend_.upload(subsetIds_, hostIds_, static_cast<size_t>(m));
        uploadedIds_.assign(ids, ids + m);
    }
    // The watched region: a coupling host reads the positions of the same particles after every step
    // call, so the call's last kernel gathers them into pinned memory and the fault check's wait
    // brings them back with it; the read then costs no launch and no wait of its own. A region the
    // host stopped reading (not read since the last gather) is no longer gathered.
    bool watching(const int64_t* ids, int64_t m) const {
        return watchedIds_.size() == static_cast<size_t>(m) && std::equal(ids, ids + m, watchedIds_.begin());
    }
    void watch(const int64_t* ids, int64_t m) {
        backend_.activate();
        if (!watching(ids, m)) {
            std::copy(ids, ids + m, hostIds_.reserve(static_cast<size_t>(m)));
            backend_.upload(watchedIdsOnBackend_, hostIds_, static_cast<size_t>(m));
            watchedIds_.assign(ids, ids + m);
        }
        watchedVersion_ = -1;
    }
    // Returns whether it gathered: the same kernel then brought the fault word along, and the step
    // call's fault check needs only to wait for it.
    bool gather_watched_positions() {
        if (watchedIds_.empty()) return false;
        if (!watchedRead_) {
            watchedIds_.clear();
            watchedIdsOnBackend_.release();
            return false;
        }
        const auto m = static_cast<int64_t>(watchedIds_.size());
        Real4<R>* values = watchedPositions_.reserve(static_cast<size_t>(m));
        backend_.for_each(m, GatherWithFaultWord<R>{p_.pos.data(), watchedIdsOnBackend_.data(), values,
                                                    p_.fault.data(), faultWord_.reserve(1)});
        backend_.written_to_host(watchedPositions_, static_cast<size_t>(m));
        backend_.written_to_host(faultWord_, 1);
        watchedVersion_ = p_.version;
        watchedRead_ = false;
        return true;
    }

    // The m values of from at the ids on the backend, in the vector staging (valid until the next
    // transfer).
    const Real4<R>* gather(const typename B::template Buffer<Real4<R>>& from,
                           const typename B::template Buffer<int64_t>& ids, int64_t m) {
        Real4<R>* values = hostVectors_.reserve(static_cast<size_t>(m));
        backend_.for_each(m, GatherById<Real4<R>>{from.data(), ids.data(), values});
        backend_.wait_for_writes_to_host(hostVectors_, static_cast<size_t>(m));
        return values;
    }
    // The m values packed in host go into to at the ids in subsetIds_.
    template <class T>
    void scatter(typename B::template Staging<T>& host, typename B::template Buffer<T>& to, int64_t m) {
        backend_.for_each(m, ScatterById<T>{host.data(), subsetIds_.data(), to.data()});
        backend_.read_from_host(host, static_cast<size_t>(m));
    }

    B backend_;
    Logger log_;
    Particles<B, R> p_;
    ForceField<B, R> forceField_;
    std::vector<std::unique_ptr<Integrator<B, R>>> integrators_;
    Schedule schedule_;
    std::vector<std::unique_ptr<SimulationStep>> steps_;
    std::vector<SimulationStep*> dueSteps_;  // those fire_steps fires, kept to reuse its memory
    StepFiring* stepFiring_ = nullptr;
    std::vector<int32_t> typeIndex_;
    std::vector<int> batchId_;
    std::vector<double> masses_;
    std::vector<double> radii_;
    std::vector<std::string> typeNames_;
    std::array<double, 3> boxLengths_{};
    double boltzmann_ = 1.0;
    double largestCutoff_ = 0.0;  // of the pair terms: the box may not shrink below twice it
    int activeStage_ = -1;        // the schedule stage whose integrator has begun
    Rollback<B, R> rollback_;
    ForceCache<B, R> cache_;
    Counters evaluations_;  // the evaluation counts; counters() adds builds and transfers
    ForceFieldContext context_;  // what the force field is made with, kept to make it again
    int64_t retiredListBuilds_ = 0;  // builds of the lists of force fields replaced by change_parameters
    double externalEnergy_ = 0.0;  // the host's field energy (structmd_set_external_energy)
    double lambda_ = 1.0;          // the value in p_.lambda, as the host set it last
    std::string stoppedBy_;  // the flow-control step that ended the last step call early
    double lambdaAtCallStart_ = 1.0;  // what a roll back to the start of the step call puts back
    typename B::template Buffer<R> lambdaDerivatives_;  // dU/dlambda by particle, made when asked
    CallbackTerm<B, R> callbacks_;  // the host's force callbacks
    // The ids of the last subset call on the backend, and on the host to compare the next with.
    typename B::template Buffer<int64_t> subsetIds_;
    typename B::template Buffer<Tensor3<R>> hessian_;        // a Hessian column, made when asked
    typename B::template Buffer<Real4<R>> probedForces_;     // forces at displaced positions, of one term or between pairs, made when asked
    typename B::template Buffer<Real4<R>> probedTorques_;    // one term's torques, made when asked
    typename B::template Buffer<R> probedEnergies_;          // one term's energies, made when asked
    bool pairForces_ = false;                                // a step reads pair_forces_on
    std::vector<int64_t> uploadedIds_;
    // Host staging of every transfer of particle arrays (pinned on CUDA): packed and unpacked here.
    typename B::template Staging<Real4<R>> hostVectors_;
    typename B::template Staging<Image> hostImages_;
    typename B::template Staging<int64_t> hostIds_;
    // The watched region (gather_watched_positions): its ids, their positions as of watchedVersion_
    // (-1: none), and whether the host read them since they were gathered.
    std::vector<int64_t> watchedIds_;
    typename B::template Buffer<int64_t> watchedIdsOnBackend_;
    typename B::template Staging<Real4<R>> watchedPositions_;
    int64_t watchedVersion_ = -1;
    bool watchedRead_ = false;
    typename B::template Staging<unsigned long long> faultWord_;
    // A spatial domain's slots (hold_ghosts), and the positions version the ghosts were last
    // refreshed at.
    DomainSlots<B, R> domain_{backend_};
    int64_t ghostsAt_ = -1;
};

}  // namespace structmd
