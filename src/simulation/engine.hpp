#pragma once
// Engine<Backend, Real>: particles, force field, integrators and simulation steps on one backend in
// one precision. It keeps track of what is current (forces, energies, virial at which positions),
// so nothing is computed twice and energies and virials only when someone asks.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/logger.hpp"
#include "core/random.hpp"
#include "forcefield/make_interactors.hpp"
#include "integrators/make_integrator.hpp"
#include "simulation/checkpoint_file.hpp"
#include "simulation/engine_functors.hpp"
#include "simulation/simulation.hpp"
#include "simulation/simulation_spec.hpp"

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
    template <class... BackendArgs>
    Engine(SimulationSpec spec, const Logger& log, BackendArgs&&... backendArgs)
        : backend_(std::forward<BackendArgs>(backendArgs)...), log_(log) {
        backend_.activate();
        boltzmann_ = spec.constants.boltzmann;
        step_ = spec.currentStep;
        firstStep_ = spec.currentStep;
        time_ = spec.simulationTime;
        schedule_ = spec.schedule;
        steps_ = std::move(spec.steps);
        typeIndex_ = spec.typeIndex;
        masses_ = spec.mass;
        p_.count = static_cast<int64_t>(spec.positions.size());
        boxLengths_ = spec.box;
        p_.box = Box<R>::make(spec.box[0], spec.box[1], spec.box[2]);

        upload_positions(flatten(spec.positions).data());
        if (spec.velocities.empty())
            upload_velocities(maxwell_boltzmann(spec).data());
        else
            upload_velocities(flatten(spec.velocities).data());
        backend_.resize(p_.force, p_.count);
        backend_.resize(p_.fault, 1);
        backend_.fill(p_.fault, kNoFault);
        set_clock();
        radii_ = spec.radius;
        typeNames_ = spec.typeNames;
        std::vector<R> radius(spec.radius.begin(), spec.radius.end());
        std::vector<R> charge(spec.charge.begin(), spec.charge.end());
        backend_.upload(p_.radius, radius.data(), radius.size());
        backend_.upload(p_.charge, charge.data(), charge.size());
        batchId_ = spec.batchId;
        if (std::any_of(batchId_.begin(), batchId_.end(), [](int b) { return b != 0; }))
            backend_.upload(p_.batch, batchId_.data(), batchId_.size());
        backend_.upload(p_.model, spec.modelId.data(), spec.modelId.size());
        p_.seed = spec.seed;

        ForceFieldContext context;
        context.ntypes = spec.typeNames.size();
        context.particles = p_.count;
        context.constants = spec.constants;
        context.batch = p_.batch.empty() ? nullptr : p_.batch.data();
        context.model = p_.model.data();
        forceField_ = make_interactors<B, R>(backend_, spec.forceField, context,
                                             builtin_interactor_factories<B, R, PairR>());
        largestCutoff_ = spec.forceField.largest_cutoff();
        for (const IntegratorSpec& integrator : spec.integrators)
            integrators_.push_back(make_integrator<B, R>(
                backend_, integrator, integrator.group >= 0 ? forceField_.group(integrator.group) : nullptr,
                builtin_integrator_factories<B, R>()));
        const double skin = forceField_.smallest_skin();
        p_.maxMove2 = std::isfinite(skin) ? skin * skin : 1e300;
        backend_.synchronize();
    }

    int64_t particle_count() const override { return p_.count; }
    int64_t current_step() const override { return step_; }
    double current_time() const override { return time_; }
    double boltzmann() const override { return boltzmann_; }
    std::array<double, 3> box() const override { return boxLengths_; }
    double volume() const override { return boxLengths_[0] * boxLengths_[1] * boxLengths_[2]; }
    int64_t final_step() const override {
        int64_t last = firstStep_;
        for (const ScheduleStage& stage : schedule_) last += stage.steps;
        return last;
    }

    void advance(int64_t n) override {
        if (n < 0) throw Error(STRUCTMD_ERR_ARGUMENT, "nsteps: expected a count >= 0, got " + std::to_string(n));
        const int64_t last = final_step();
        if (step_ + n > last)
            throw Error(STRUCTMD_ERR_STATE, "cannot advance " + std::to_string(n) + " steps from step " +
                                                std::to_string(step_) + ": the schedule ends at step " +
                                                std::to_string(last));
        if (n == 0) return;
        backend_.activate();
        save_state();
        backend_.begin_steps();
        try {
            for (int64_t k = 0; k < n; ++k) {
                if (k > 0 && k % kStepsPerGraph == 0) {
                    backend_.end_steps();
                    backend_.begin_steps();
                }
                fire_steps(false);
                const int stage = current_stage();
                Integrator<B, R>& integrator = *integrators_[schedule_[stage].integrator];
                if (stage != activeStage_) {
                    integrator.begin(p_, *this);
                    activeStage_ = stage;
                }
                integrator.step(p_, *this);
                ++step_;
                time_ += integrator.time_advance();
                backend_.for_each(1, AdvanceClock{p_.clock.data(), integrator.time_advance()});
                p_.clockAtLaunch = {step_, time_};
                p_.step = step_;
                p_.time = time_;
            }
        } catch (...) {
            backend_.end_steps();
            throw;
        }
        backend_.end_steps();
        check_fault();
        if (step_ == last) fire_steps(true);
        forceField_.adapt();
    }

    void compute(unsigned flags) override {
        backend_.activate();
        evaluate(flags);
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
    void get_radii(double* r) override { std::copy(radii_.begin(), radii_.end(), r); }
    const std::vector<std::string>& type_names() const override { return typeNames_; }
    // A failed getter leaves the caller's array alone: the forces are checked before they are handed over.
    void get_forces(double* f) override {
        compute(kForces);
        std::vector<double> values(3 * p_.count);
        download_vectors(p_.force, values.data());
        for (int64_t k = 0; k < 3 * p_.count; ++k)
            if (!std::isfinite(values[k]))
                throw Error(STRUCTMD_ERR_NUMERICAL, "step " + std::to_string(step_) + ", particle id " +
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
    void get_masses(double* m) override { std::copy(masses_.begin(), masses_.end(), m); }
    void get_types(int32_t* types) override { std::copy(typeIndex_.begin(), typeIndex_.end(), types); }

    // A term may end in "@batch:K" for the share of the particles of batch K.
    double energy(const std::string& request) override {
        backend_.activate();
        std::string term = request;
        int batch = -1;
        const size_t at = request.find("@batch:");
        if (at != std::string::npos) {
            term = request.substr(0, at);
            batch = parse_batch(request.substr(at + 7), request);
        }
        if (term == "kinetic") return kinetic_energy(batch);
        if (term == "potential") return potential_energy(batch);
        if (term == "total") return kinetic_energy(batch) + potential_energy(batch);
        const int index = forceField_.find(term);
        if (index < 0) {
            std::string known = "potential, kinetic, total";
            for (const std::string& name : forceField_.names()) known += ", " + name;
            throw Error(STRUCTMD_ERR_ARGUMENT, "energy term '" + request + "' does not exist (terms: " + known +
                                                   ", each optionally followed by @batch:K)");
        }
        backend_.resize(p_.energy, p_.count);
        backend_.fill(p_.energy, R(0));
        ForceOutputs<R> out;
        out.energy = p_.energy.data();
        forceField_.compute_one(index, p_, out);
        count(out);
        energyVersion_ = -1;  // the buffer now holds one term only
        return sum_energy(batch);
    }
    std::vector<std::string> energy_terms() const override { return forceField_.names(); }

    std::array<double, 9> virial() override {
        compute(kVirial);
        const Tensor3<double> w =
            backend_.reduce(p_.count, SumVirial<R>{p_.virial.data()}, zero_tensor<double>());
        return {w.xx, w.xy, w.xz, w.yx, w.yy, w.yz, w.zx, w.zy, w.zz};
    }

    void get_pair_virials(double* w) override {
        backend_.activate();
        backend_.resize(p_.virial, p_.count);
        backend_.fill(p_.virial, zero_tensor<R>());
        ForceOutputs<R> out;
        out.virial = p_.virial.data();
        forceField_.compute_pairwise(p_, out);
        count(out);
        virialVersion_ = -1;  // the buffer now holds the pair terms only
        std::vector<Tensor3<R>> values(p_.count);
        backend_.download(p_.virial, values.data(), values.size());
        for (int64_t i = 0; i < p_.count; ++i) {
            const Tensor3<R>& t = values[i];
            const R row[9] = {t.xx, t.xy, t.xz, t.yx, t.yy, t.yz, t.zx, t.zy, t.zz};
            std::copy(row, row + 9, w + 9 * i);
        }
    }

    void set_positions(const double* xyz) override {
        backend_.activate();
        upload_positions(xyz);
        ++p_.version;
        forceField_.invalidate_lists();
    }
    void set_velocities(const double* v) override {
        backend_.activate();
        upload_velocities(v);
    }
    void set_box(const double lengths[3]) override {
        backend_.activate();
        for (int d = 0; d < 3; ++d)
            if (!(lengths[d] > 0.0 && lengths[d] <= 1e15))
                throw Error(STRUCTMD_ERR_ARGUMENT, "lengths[" + std::to_string(d) + "]: expected a box length > 0 and "
                                                   "<= 1e15, got " + precise(lengths[d]));
        if (!cutoff_fits_box(largestCutoff_, {lengths[0], lengths[1], lengths[2]}))
            throw Error(STRUCTMD_ERR_ARGUMENT, "lengths: the largest cutoff (" + precise(largestCutoff_) +
                                                   ") must be shorter than half the box (" +
                                                   precise(0.5 * std::min({lengths[0], lengths[1], lengths[2]})) + ")");
        std::vector<double> xyz(3 * p_.count);
        get_unwrapped_positions(xyz.data());
        for (int64_t i = 0; i < p_.count; ++i)
            for (int d = 0; d < 3; ++d) xyz[3 * i + d] *= lengths[d] / boxLengths_[d];
        boxLengths_ = {lengths[0], lengths[1], lengths[2]};
        p_.box = Box<R>::make(lengths[0], lengths[1], lengths[2]);
        set_positions(xyz.data());
    }
    void set_external_forces(const double* f) override {
        backend_.activate();
        if (f == nullptr) {
            p_.externalForce.release();
        } else {
            std::vector<Real4<R>> values(p_.count);
            for (int64_t i = 0; i < p_.count; ++i)
                values[i] = {R(f[3 * i]), R(f[3 * i + 1]), R(f[3 * i + 2]), R(0)};
            backend_.upload(p_.externalForce, values.data(), values.size());
        }
        forcesVersion_ = -1;
    }

    void save_checkpoint(const std::string& path) override {
        backend_.activate();
        ByteWriter out;
        out.put(static_cast<uint32_t>(sizeof(R)));
        out.put(p_.count);
        out.put(firstStep_);
        out.put(step_);
        out.put(time_);
        out.put(static_cast<int32_t>(activeStage_));
        for (double length : boxLengths_) out.put(length);
        put_buffer(out, p_.pos);
        put_buffer(out, p_.image);
        put_buffer(out, p_.vel);
        out.put(static_cast<uint8_t>(!p_.externalForce.empty()));
        if (!p_.externalForce.empty()) put_buffer(out, p_.externalForce);
        for (const auto& integrator : integrators_) {
            const std::vector<double> state = integrator->state();
            out.put(static_cast<uint32_t>(state.size()));
            out.put_bytes(state.data(), state.size() * sizeof(double));
        }
        write_checkpoint_file(path, out.bytes());
    }

    void load_checkpoint(const std::string& path) override {
        const std::vector<unsigned char> payload = read_checkpoint_file(path);
        ByteReader in(payload, path);
        const auto mismatch = [&](const std::string& what) {
            return Error(STRUCTMD_ERR_IO, "checkpoint '" + path + "' does not fit this simulation: " + what);
        };
        const uint32_t realSize = in.get<uint32_t>();
        if (realSize != sizeof(R))
            throw mismatch(std::string("it was written in ") + (realSize == 4 ? "single" : "double") +
                           " precision, this simulation runs in " + precision_label<R, PairR>());
        const int64_t count = in.get<int64_t>();
        if (count != p_.count)
            throw mismatch("it holds " + std::to_string(count) + " particles, this simulation " + std::to_string(p_.count));
        const int64_t firstStep = in.get<int64_t>();
        if (firstStep != firstStep_)
            throw mismatch("its schedule starts at step " + std::to_string(firstStep) + ", this one at " +
                           std::to_string(firstStep_));
        const int64_t step = in.get<int64_t>();
        const double time = in.get<double>();
        const int32_t activeStage = in.get<int32_t>();
        std::array<double, 3> box{};
        for (double& length : box) length = in.get<double>();
        if (step < firstStep_ || step > final_step() || activeStage < -1 ||
            activeStage >= static_cast<int32_t>(schedule_.size()) || !(box[0] > 0 && box[1] > 0 && box[2] > 0))
            throw mismatch("its step, schedule stage or box is out of range");
        std::vector<Real4<R>> pos(p_.count), vel(p_.count), external;
        std::vector<Image> image(p_.count);
        in.get_bytes(pos.data(), pos.size() * sizeof(Real4<R>));
        in.get_bytes(image.data(), image.size() * sizeof(Image));
        in.get_bytes(vel.data(), vel.size() * sizeof(Real4<R>));
        if (in.get<uint8_t>()) {
            external.resize(p_.count);
            in.get_bytes(external.data(), external.size() * sizeof(Real4<R>));
        }
        std::vector<std::vector<double>> states(integrators_.size());
        for (auto& state : states) {
            state.resize(in.get<uint32_t>());
            in.get_bytes(state.data(), state.size() * sizeof(double));
        }
        if (!in.at_end()) throw mismatch("it has more data than this simulation's integrators hold");

        // Everything read and checked: now the state changes.
        backend_.activate();
        boxLengths_ = box;
        p_.box = Box<R>::make(box[0], box[1], box[2]);
        backend_.upload(p_.pos, pos.data(), pos.size());
        backend_.upload(p_.image, image.data(), image.size());
        backend_.upload(p_.vel, vel.data(), vel.size());
        if (external.empty())
            p_.externalForce.release();
        else
            backend_.upload(p_.externalForce, external.data(), external.size());
        for (size_t k = 0; k < integrators_.size(); ++k) integrators_[k]->restore(states[k]);
        step_ = step;
        time_ = time;
        activeStage_ = activeStage;
        set_clock();
        ++p_.version;
        forcesVersion_ = energyVersion_ = virialVersion_ = -1;
        forceField_.invalidate_lists();
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
        c.neighbourListBuilds = static_cast<uint64_t>(forceField_.builds());
        return c;
    }

    std::string backend_name() const override { return B::name; }
    std::string precision_name() const override { return precision_label<R, PairR>(); }
    std::string device_name() const override { return backend_.device_name(); }
    int threads() const override { return backend_.threads(); }

private:
    // Steps per CUDA graph: enough to make the launch of the graph negligible, few enough that the
    // graph stays small and the last, shorter batch of a call is cheap to capture.
    static constexpr int64_t kStepsPerGraph = 16;

    // The step and time on the host and on the backend's clock agree again.
    void set_clock() {
        p_.step = step_;
        p_.time = time_;
        p_.clockAtLaunch = {step_, time_};
        backend_.upload(p_.clock, &p_.clockAtLaunch, 1);
    }

    // ForceSource
    void update_forces() override { evaluate(kForces); }
    double potential_energy() override { return potential_energy(-1); }
    void positions_moved(double elapsed) override {
        ++p_.version;
        p_.step = step_ + 1;
        p_.time = time_ + elapsed;
    }

    // Evaluates, in one pass over the force field, whichever of forces, energies and virial asked
    // for in flags are stale.
    void evaluate(unsigned flags) {
        ForceOutputs<R> out;
        if ((flags & kForces) && forcesVersion_ != p_.version) {
            backend_.for_each(p_.count, InitForces<R>{p_.force.data(), p_.externalForce.empty()
                                                                          ? nullptr
                                                                          : p_.externalForce.data()});
            out.force = p_.force.data();
        }
        if ((flags & kEnergy) && energyVersion_ != p_.version) {
            backend_.resize(p_.energy, p_.count);
            backend_.fill(p_.energy, R(0));
            out.energy = p_.energy.data();
        }
        if ((flags & kVirial) && virialVersion_ != p_.version) {
            backend_.resize(p_.virial, p_.count);
            backend_.fill(p_.virial, zero_tensor<R>());
            out.virial = p_.virial.data();
        }
        if (!out.force && !out.energy && !out.virial) return;
        forceField_.prepare(p_);
        forceField_.compute_all(p_, out);
        count(out);
        if (out.force) forcesVersion_ = p_.version;
        if (out.energy) energyVersion_ = p_.version;
        if (out.virial) virialVersion_ = p_.version;
    }

    // The state a step call starts from, on the backend, so that a blow-up can be undone.
    struct SavedState {
        typename B::template Buffer<Real4<R>> pos, vel;
        typename B::template Buffer<Image> image;
        int64_t step = 0;
        double time = 0.0;
        int activeStage = -1;
        std::vector<std::vector<double>> integrators;
    };

    void save_state() {
        backend_.resize(saved_.pos, p_.count);
        backend_.resize(saved_.vel, p_.count);
        backend_.resize(saved_.image, p_.count);
        backend_.for_each(p_.count, CopyState<R>{p_.pos.data(), p_.image.data(), p_.vel.data(), saved_.pos.data(),
                                                 saved_.image.data(), saved_.vel.data()});
        saved_.step = step_;
        saved_.time = time_;
        saved_.activeStage = activeStage_;
        saved_.integrators.clear();
        for (const auto& integrator : integrators_) saved_.integrators.push_back(integrator->state());
    }

    void restore_state() {
        backend_.for_each(p_.count, CopyState<R>{saved_.pos.data(), saved_.image.data(), saved_.vel.data(),
                                                 p_.pos.data(), p_.image.data(), p_.vel.data()});
        for (size_t k = 0; k < integrators_.size(); ++k) integrators_[k]->restore(saved_.integrators[k]);
        step_ = saved_.step;
        time_ = saved_.time;
        activeStage_ = saved_.activeStage;
        set_clock();
        ++p_.version;
        forcesVersion_ = energyVersion_ = virialVersion_ = -1;
        forceField_.invalidate_lists();
    }

    // Reports a fault recorded on the backend during the last steps, naming the first step, particle
    // and quantity, and returns to the state the call started from, so that the getters show the
    // last good state and the host can go on from it (with a smaller time step, say).
    void check_fault() {
        const unsigned long long word = backend_.read(p_.fault, 0);
        if (word == kNoFault) return;
        backend_.fill(p_.fault, kNoFault);
        const int64_t failedStep = step_;
        restore_state();
        const int64_t step = FaultSlot::step_of(word);
        const int64_t id = FaultSlot::particle_of(word);
        std::string what;
        switch (FaultSlot::quantity_of(word)) {
            case FaultQuantity::position: what = "the position is not finite"; break;
            case FaultQuantity::velocity: what = "the velocity is not finite"; break;
            case FaultQuantity::force: what = "the force is not finite"; break;
            case FaultQuantity::displacement:
                what = "the displacement in one step is longer than the neighbour-list skin (" +
                       std::to_string(std::sqrt(p_.maxMove2)) + ")";
                break;
        }
        throw Error(STRUCTMD_ERR_NUMERICAL,
                    "step " + std::to_string(step) + ", particle id " + std::to_string(id) + ": " + what +
                        ": the simulation blew up (time step too large, or overlapping particles); the run went on to "
                        "step " + std::to_string(failedStep) + ", and the state is back at step " +
                        std::to_string(step_) + ", where this call started: repair it (structmd_set_positions, "
                        "structmd_set_velocities, a checkpoint) or step on with a smaller time step");
    }

    int parse_batch(const std::string& text, const std::string& request) const {
        size_t used = 0;
        int batch = -1;
        try {
            batch = std::stoi(text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != text.size() || std::find(batchId_.begin(), batchId_.end(), batch) == batchId_.end())
            throw Error(STRUCTMD_ERR_ARGUMENT, "energy term '" + request + "': no particle has batchId '" + text + "'");
        return p_.batch.empty() ? -1 : batch;  // one batch: its share is everything
    }

    // batch < 0: all particles.
    void count(const ForceOutputs<R>& out) {
        evaluations_.forceEvaluations += out.force != nullptr;
        evaluations_.energyEvaluations += out.energy != nullptr;
        evaluations_.virialEvaluations += out.virial != nullptr;
    }

    double sum_energy(int batch) {
        if (batch < 0) return backend_.reduce(p_.count, SumEnergy<R>{p_.energy.data()}, 0.0);
        return backend_.reduce(p_.count, InBatch<SumEnergy<R>>{{p_.energy.data()}, p_.batch.data(), batch}, 0.0);
    }
    double potential_energy(int batch) {
        evaluate(kEnergy);
        return sum_energy(batch);
    }
    double kinetic_energy(int batch) {
        if (batch < 0) return backend_.reduce(p_.count, KineticEnergy<R>{p_.vel.data()}, 0.0);
        return backend_.reduce(p_.count, InBatch<KineticEnergy<R>>{{p_.vel.data()}, p_.batch.data(), batch}, 0.0);
    }

    // The schedule row the next step belongs to.
    int current_stage() const {
        int64_t offset = step_ - firstStep_;
        for (size_t k = 0; k < schedule_.size(); ++k) {
            if (offset < schedule_[k].steps) return static_cast<int>(k);
            offset -= schedule_[k].steps;
        }
        throw Error(STRUCTMD_ERR_INTERNAL, "no integrator scheduled at step " + std::to_string(step_));
    }

    // Simulation steps see the state before the step is taken; the final state of the schedule
    // is given to every step whose window holds it.
    void fire_steps(bool final) {
        for (auto& s : steps_)
            if (final ? s->in_window(step_) : s->due(step_)) s->fire(*this);
    }

    // All the digits a double needs, so that two numbers that differ never print alike.
    static std::string precise(double x) {
        char text[32];
        std::snprintf(text, sizeof text, "%.17g", x);
        return text;
    }

    static std::vector<double> flatten(const std::vector<std::array<double, 3>>& vectors) {
        std::vector<double> flat;
        flat.reserve(3 * vectors.size());
        for (const auto& v : vectors) flat.insert(flat.end(), v.begin(), v.end());
        return flat;
    }

    // Maxwell-Boltzmann velocities at the first integrator's temperature (by default the ensemble's),
    // keyed by (seed, particle id), with the centre-of-mass momentum removed so the system does not
    // drift.
    std::vector<double> maxwell_boltzmann(const SimulationSpec& spec) const {
        const double kT = spec.velocityKT;
        std::vector<double> v(3 * p_.count);
        double momentum[3] = {0, 0, 0};
        double totalMass = 0;
        for (int64_t i = 0; i < p_.count; ++i) {
            double normal[4];
            normal4(spec.seed, static_cast<uint64_t>(i), 0, normal);
            const double sigma = std::sqrt(kT / spec.mass[i]);
            for (int d = 0; d < 3; ++d) {
                v[3 * i + d] = sigma * normal[d];
                momentum[d] += spec.mass[i] * v[3 * i + d];
            }
            totalMass += spec.mass[i];
        }
        if (p_.count > 1)
            for (int64_t i = 0; i < p_.count; ++i)
                for (int d = 0; d < 3; ++d) v[3 * i + d] -= momentum[d] / totalMass;
        return v;
    }

    // Wraps the given positions into the box; their images count the box lengths removed, so the
    // unwrapped positions are the ones given.
    void upload_positions(const double* xyz) {
        const Box<double> box = Box<double>::make(boxLengths_[0], boxLengths_[1], boxLengths_[2]);
        std::vector<Real4<R>> values(p_.count);
        std::vector<Image> images(p_.count, Image{0, 0, 0});
        for (int64_t i = 0; i < p_.count; ++i) {
            for (int d = 0; d < 3; ++d) {
                const double x = xyz[3 * i + d];
                if (!std::isfinite(x) || std::fabs(x) > 1e8 * boxLengths_[d])
                    throw Error(STRUCTMD_ERR_ARGUMENT,
                                "position of particle id " + std::to_string(i) + ": coordinate " + std::to_string(d) +
                                    " is " + precise(x) +
                                    ": expected a finite value within 1e8 box lengths of the box");
            }
            const Vec3<double> r = box.wrap({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, images[i]);
            values[i] = {R(r.x), R(r.y), R(r.z), R(typeIndex_[i])};
        }
        backend_.upload(p_.pos, values.data(), values.size());
        backend_.upload(p_.image, images.data(), images.size());
    }

    void upload_velocities(const double* v) {
        std::vector<Real4<R>> values(p_.count);
        for (int64_t i = 0; i < p_.count; ++i)
            values[i] = {R(v[3 * i]), R(v[3 * i + 1]), R(v[3 * i + 2]), R(masses_[i])};
        backend_.upload(p_.vel, values.data(), values.size());
    }

    template <class T>
    void put_buffer(ByteWriter& out, const typename B::template Buffer<T>& buffer) {
        std::vector<T> values(buffer.size());
        backend_.download(buffer, values.data(), values.size());
        out.put_bytes(values.data(), values.size() * sizeof(T));
    }

    void download_vectors(const typename B::template Buffer<Real4<R>>& buffer, double* out) {
        backend_.activate();
        std::vector<Real4<R>> values(p_.count);
        backend_.download(buffer, values.data(), values.size());
        for (int64_t i = 0; i < p_.count; ++i) {
            out[3 * i] = values[i].x;
            out[3 * i + 1] = values[i].y;
            out[3 * i + 2] = values[i].z;
        }
    }

    B backend_;
    Logger log_;
    Particles<B, R> p_;
    ForceField<B, R> forceField_;
    std::vector<std::unique_ptr<Integrator<B, R>>> integrators_;
    std::vector<ScheduleStage> schedule_;
    std::vector<std::unique_ptr<SimulationStep>> steps_;
    std::vector<int32_t> typeIndex_;
    std::vector<int> batchId_;
    std::vector<double> masses_;
    std::vector<double> radii_;
    std::vector<std::string> typeNames_;
    std::array<double, 3> boxLengths_{};
    double boltzmann_ = 1.0;
    double largestCutoff_ = 0.0;  // of the pair terms: the box may not shrink below twice it
    int64_t step_ = 0;
    int64_t firstStep_ = 0;
    int activeStage_ = -1;  // the schedule row whose integrator has begun
    SavedState saved_;
    Counters evaluations_;  // the evaluation counts; counters() adds builds and transfers
    double time_ = 0.0;
    // Versions: what each cached quantity was computed at (-1: never or invalid).
    int64_t forcesVersion_ = -1;
    int64_t energyVersion_ = -1;
    int64_t virialVersion_ = -1;
};

}  // namespace structmd
