#pragma once
// Engine<Backend, Real>: particles, force field, integrators and simulation steps on one backend in
// one precision, and the step loop. What the engine owns and the loop are here; its other jobs are
// defined beside it, each in a file of its own: the per-particle accessor (engine_particles.hpp),
// the probes of simulation steps (engine_probes.hpp), a spatial domain's slots (engine_domain.hpp)
// and energies, checkpoints and parameter changes (engine_state.hpp). Its parts: what is current
// (force_cache.hpp), the state a call can roll back to (rollback.hpp), transfers (particle_io.hpp),
// energy terms (energy_terms.hpp) and the schedule (schedule.hpp); the step and time have one
// owner, the particles' Timeline.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/logger.hpp"
#include "core/precise.hpp"
#include "forcefield/builtin_factories.hpp"
#include "forcefield/component_set.hpp"
#include "forcefield/make_interactors.hpp"
#include "integrators/make_integrator.hpp"
#include "simulation/callback_term.hpp"
#include "simulation/domain_slots.hpp"
#include "simulation/energy_terms.hpp"
#include "simulation/engine_functors.hpp"
#include "simulation/fault_report.hpp"
#include "simulation/force_cache.hpp"
#include "simulation/local_engine.hpp"
#include "simulation/particle_io.hpp"
#include "simulation/prepared_expression_sum.hpp"
#include "simulation/read_simulation.hpp"
#include "simulation/rollback.hpp"
#include "simulation/schedule.hpp"
#include "simulation/simulation_spec.hpp"
#include "steps/simulation_step.hpp"

namespace structmd {

// R: positions, velocities, forces and sums; PairR: the arithmetic of non-bonded pair terms.
template <class R, class PairR>
constexpr const char* precision_label() {
    if constexpr (sizeof(R) == sizeof(PairR)) return sizeof(R) == sizeof(float) ? "single" : "double";
    return "mixed";
}

// What the host keeps of the particles by slot, as the input gave them; a spatial domain's view
// answers for its slots once it renumbered them.
struct HostAttributes {
    std::vector<int32_t> typeIndex;
    std::vector<int> batchId;
    std::vector<double> masses, radii;
    std::vector<std::string> typeNames;
};

// The simulation steps and who fires them (StepFiring; the engine itself by default).
struct EngineSteps {
    std::vector<std::unique_ptr<SimulationStep>> all;
    std::vector<SimulationStep*> due;  // those firing now, kept to reuse its memory
    StepFiring* firing = nullptr;
    std::string stoppedBy;  // the flow-control step that ended the last step call early
};

// What the probes of simulation steps compute into, each made when first asked for.
template <class B, class R>
struct ProbeBuffers {
    typename B::template Buffer<Tensor3<R>> hessian;      // a Hessian column
    typename B::template Buffer<Real4<R>> forces;         // of one term, between pairs, or displaced
    typename B::template Buffer<Real4<R>> torques;        // one term's
    typename B::template Buffer<R> energies;              // one term's
    typename B::template Buffer<R> lambdaDerivatives;     // dU/dlambda by particle
    bool pairForces = false;                              // a step reads pair_forces_on
};

template <class B, class R, class PairR = R>
class Engine final : public LocalEngine, private ForceSource {
public:
    // `components`: the handle's force-field components (built-ins and its plugins'), whose
    // factories build the force field.
    template <class... BackendArgs>
    Engine(SimulationSpec spec, const ForceFieldComponents& components, const Logger& log, BackendArgs&&... backendArgs)
        : backend_(std::forward<BackendArgs>(backendArgs)...),
          log_(log),
          schedule_(spec.currentStep, spec.schedule),
          host_{spec.typeIndex, spec.batchId, spec.mass, spec.radius, spec.typeNames},
          boxLengths_(spec.box),
          boltzmann_(spec.constants.boltzmann),
          largestCutoff_(spec.forceField.largest_cutoff()),
          stepGraphs_(spec.stepGraphs) {
        steps_.all = std::move(spec.steps);
        backend_.activate();
        load_particles(spec);
        context_.constants.lambda = p_.lambda.data();
        context_.log = &log_;
        const auto hessianStep = std::find_if(steps_.all.begin(), steps_.all.end(), [](const auto& s) { return s->needs_hessian(); });
        context_.hessian = hessianStep != steps_.all.end();
        forceField_ = make_force_field(spec.forceField, components, nullptr);
        for (const GroupSpec& g : spec.forceField.groups) groupNames_.push_back(g.name);
        const auto pairForceStep = std::find_if(steps_.all.begin(), steps_.all.end(), [](const auto& s) { return s->needs_pair_forces(); });
        probed_.pairForces = pairForceStep != steps_.all.end();
        if (const std::string term = forceField_.term_without_pair_forces(); probed_.pairForces && !term.empty())
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
        limit_moves();
        backend_.synchronize();
    }

    int64_t particle_count() const override { return p_.count; }
    int64_t massive_count() const override {
        slot_copies_on_host();
        return std::count_if(host_.masses.begin(), host_.masses.end(), [](double m) { return m > 0.0; });
    }
    ScheduleClock clock() const override { return {p_.timeline.step(), p_.timeline.time(), schedule_.final_step()}; }
    double boltzmann() const override { return boltzmann_; }
    std::array<double, 3> box() const override { return boxLengths_; }
    const std::vector<std::string>& type_names() const override { return host_.typeNames; }
    std::optional<double> overdamped_kT() const override {
        if (schedule_.stages() == 0) return std::nullopt;
        const Integrator<B, R>& next = *integrators_[schedule_.integrator_of(schedule_.stage_after(current_step()))];
        if (!next.overdamped()) return std::nullopt;
        return next.thermal_energy();
    }
    EngineDescription description() const override {
        return {B::name, precision_label<R, PairR>(), backend_.device_name(), backend_.threads()};
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
        steps_.stoppedBy.clear();
        if (stepGraphs_) backend_.begin_steps();
        try {
            bool endOwed = false;  // the last step left its end to this one (Integrator::join_steps)
            for (int64_t k = 0; k < n; ++k) {
                if (stepGraphs_) backend_.begin_step();
                fire_steps(current_step() == last);  // the schedule's final state, passed through
                if (!steps_.stoppedBy.empty()) break;
                const int stage = schedule_.stage_after(current_step());
                Integrator<B, R>& integrator = *integrators_[schedule_.integrator_of(stage)];
                if (stage != activeStage_) {
                    integrator.begin(p_, *this);
                    activeStage_ = stage;
                }
                const bool joinsNext = k + 1 < n && integrator.joins_steps() && unobserved_before(current_step() + 1, stage);
                integrator.join_steps({endOwed, joinsNext});
                integrator.step(p_, *this);
                endOwed = joinsNext;
                evaluations_.stepsJoined += joinsNext ? 1 : 0;
                backend_.for_each(1, AdvanceClock{p_.clock.data(), integrator.time_advance()});
                p_.timeline.commit(integrator.time_advance());
            }
        } catch (const Error& e) {
            end_step_graphs();
            // A host callback that fails stops the call as a blow-up does: back to its start.
            if (e.status() == STRUCTMD_ERR_CALLBACK) roll_back();
            throw;
        } catch (...) {
            end_step_graphs();
            throw;
        }
        end_step_graphs();
        check_fault(io_.gather_watched_positions());
        // What is due at the step the call ends on is written now, as LAMMPS and OpenMM do, not at
        // the start of a next call that a host may never make.
        fire_steps(current_step() == last);
        forceField_.adapt();
    }
    void request_stop(const std::string& by) override {
        if (steps_.stoppedBy.empty()) steps_.stoppedBy = by;
    }
    const std::string& stopped_by() const override { return steps_.stoppedBy; }
    void compute(unsigned flags) override {
        backend_.activate();
        refresh_ghosts();
        cache_.evaluate(flags, backend_, p_, forceField_, callbacks_, evaluations_);
    }

    void read(PerParticle q, double* out) override;
    void write(PerParticle q, const double* in) override;
    void read_of(PerParticle q, const int64_t* ids, int64_t m, double* out) override;
    void write_of(PerParticle q, const int64_t* ids, int64_t m, const double* in) override;
    ArrayView view(const std::string& quantity) override;

    double energy(const std::string& request) override;
    std::vector<std::string> energy_terms() const override { return forceField_.names(); }
    std::array<double, 9> virial() override;
    void set_external_energy(double energy) override { externalEnergy_ = energy; }

    void set_box(const double lengths[3]) override;
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
    void set_force_callback(ForceCallback callback) override {
        if (auto* host = std::get_if<HostForceCallback>(&callback))
            callbacks_.set_host(std::move(*host));
        else
            callbacks_.set_device(std::move(std::get<DeviceForceCallback>(callback)));
        cache_.invalidate();
    }

    void change_parameters(const RuntimeSpec& spec, const ForceFieldComponents& components) override;
    void save_checkpoint(const std::string& path) override;
    void load_checkpoint(const std::string& path) override;

    // SimulationProbes (engine_probes.hpp)
    void term_energies_and_forces(const std::string& term, double* energies, double* forces,
                                  double* torques) override;
    void hessian_column(int64_t id, double* blocks) override;
    void pair_forces_on(int64_t id, double* f) override;
    void forces_with_displaced(int64_t id, const double displacement[3], double* f) override;
    double lambda_derivative() override;
    std::vector<int> patch_bonds(const std::string& entry) override;
    bool has_magnetization() const override { return !p_.magnetization.empty(); }
    void expression_sum(const ExpressionTransverserSpec& spec, double* perParticle) override;  // engine_transversers.hpp
    void traverse(const TransverserCall& call, double* perParticle) override;                 // engine_transversers.hpp
    TransverserOutput traverse_on_backend(const TransverserCall& call) override;             // engine_transversers.hpp

    // DomainMember (engine_domain.hpp)
    void set_step_firing(StepFiring* firing) override { steps_.firing = firing; }
    void take_steps(std::vector<std::unique_ptr<SimulationStep>>& into) override {
        for (auto& step : steps_.all) into.push_back(std::move(step));
        steps_.all.clear();
    }
    double list_radius() const override { return forceField_.largest_list_radius(); }
    double pair_cutoff() const override { return largestCutoff_; }
    void hold_ghosts(const DomainLayout& layout, GhostExchange* exchange, bool begun) override;
    double largest_owned_move() override;
    SlabSort sort_owned(const SlabGeometry& geometry) override;
    std::vector<std::vector<int64_t>> place_owned(const std::vector<Migrant>& arrivals,
                                                  const SlotAttributes& attributes) override;
    void place_ghosts(const std::vector<int64_t>& ghostIds, const SlotAttributes& attributes,
                      const DomainTerms& terms) override;
    std::vector<int64_t> global_ids() override;

private:
    // The particles' arrays and the force field's context from the spec.
    void load_particles(const SimulationSpec& spec);
    // Orientations of every particle at the identity.
    void create_orientations();
    // The host's field, zero until it sets one; replace_external_forces puts m values in (at `ids`,
    // or every particle for null ids).
    void create_external_forces();
    void replace_external_forces(const int64_t* ids, const Real4<R>* values, int64_t m);

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
    // The neighbour lists' skin bounds a step's move (FaultSlot); no limit without lists.
    void limit_moves() {
        const double skin = forceField_.smallest_skin();
        p_.maxMove2 = std::isfinite(skin) ? skin * skin : 1e300;
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
        if (p_.drift.slotOf) forceField_.drift_mirrored(p_.version, p_.drift.mirror.positions != nullptr);
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

    // What the next drift kernel can take over (state/drift_bookkeeping.hpp): clearing the forces,
    // unless torques are kept (they are cleared with them) or the first term stores them
    // (ForceOutputs::storeForce), and the first list's position copy.
    void arm_drift() {
        DriftBookkeeping<R> drift;
        if (p_.torque.empty() && !forceField_.first_term_stores_forces(p_)) {
            drift.force = p_.force.data();
            drift.external = p_.externalForce.empty() ? nullptr : p_.externalForce.data();
        }
        forceField_.mirror_in_drift(drift, p_);
        p_.drift = drift;
    }

    // A spatial domain's view answers for its slots' types, masses and radii once it renumbered them.
    void slot_copies_on_host() const {
        if (domain_.held() && static_cast<int64_t>(host_.masses.size()) != p_.count)
            throw Error(STRUCTMD_ERR_INTERNAL, "a spatial domain's engine keeps no host copy of its slots' attributes");
    }
    // A spatial domain's ghosts take their owners' positions whenever the positions moved since
    // they last did (collective: every rank's engine makes the same calls). Their own drift moved
    // them with incomplete forces; the new positions are a new version, so the lists check them
    // afresh.
    void refresh_ghosts() {
        if (!domain_.held() || ghostsAt_ == p_.version) return;
        domain_.refresh(p_, io_.vector_staging());
        ++p_.version;
        ghostsAt_ = p_.version;
    }

    // Reports a fault recorded on the backend during the last steps and returns to the state the
    // call started from. faultStaged: a kernel queued last copies the fault word into the staging.
    void check_fault(bool faultStaged = false) {
        const unsigned long long word = faultStaged ? io_.staged_fault_word() : backend_.read(p_.fault, 0);
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

    // Sums over the particles of one batch (batch < 0: all), the host's parts aside.
    double sum_energy(int batch);
    double potential_energy(int batch);
    double kinetic_energy(int batch);

    // Closes the call's last step graph, which runs what was recorded since the one before.
    void end_step_graphs() {
        if (stepGraphs_) backend_.end_steps();
    }

    // Whether the state between this step and the one that starts at `next` goes unseen, so that the
    // integrator may leave the end of this one to the next: the same stage runs it, no simulation
    // step fires before it (fire_steps), and no force callback is set (a device callback could read
    // the velocities through a view the host kept).
    bool unobserved_before(int64_t next, int stage) const {
        if (!callbacks_.empty() || schedule_.stage_after(next) != stage) return false;
        const bool final = next == final_step();
        return std::none_of(steps_.all.begin(), steps_.all.end(),
                            [&](const auto& s) { return final ? s->in_window(next) : s->due(next); });
    }

    // Simulation steps see the state before the step is taken; the final state of the schedule
    // is given to every step whose window holds it.
    void fire_steps(bool final) {
        steps_.due.clear();
        for (auto& s : steps_.all)
            if (final ? s->in_window(current_step()) : s->due(current_step())) steps_.due.push_back(s.get());
        if (steps_.due.empty()) return;
        if (steps_.firing) {
            steps_.firing->fire(steps_.due);
            return;
        }
        for (SimulationStep* s : steps_.due) s->fire(*this);
    }

    B backend_;
    Logger log_;
    Particles<B, R> p_;
    ParticleIo<B, R> io_{backend_, p_};
    ForceField<B, R> forceField_;
    std::vector<std::unique_ptr<Integrator<B, R>>> integrators_;
    Schedule schedule_;
    EngineSteps steps_;
    HostAttributes host_;
    std::array<double, 3> boxLengths_{};
    double boltzmann_ = 1.0;
    double largestCutoff_ = 0.0;  // of the pair terms: the box may not shrink below twice it
    bool stepGraphs_ = true;      // the engine option "step_graphs"
    int activeStage_ = -1;        // the schedule stage whose integrator has begun
    Rollback<B, R> rollback_;
    ForceCache<B, R> cache_;
    Counters evaluations_;       // the evaluation counts; counters() adds builds and transfers
    ForceFieldContext context_;  // what the force field is made with, kept to make it again
    int64_t retiredListBuilds_ = 0;   // builds of the lists of force fields replaced since load
    double externalEnergy_ = 0.0;     // the host's field energy (structmd_set_external_energy)
    double lambda_ = 1.0;             // the value in p_.lambda, as the host set it last
    double lambdaAtCallStart_ = 1.0;  // what a roll back to the start of the step call puts back
    CallbackTerm<B, R> callbacks_;    // the host's force callbacks
    ProbeBuffers<B, R> probed_;
    // The expression transversers run so far, by key (ExpressionTransverserSpec::key).
    std::vector<std::pair<std::string, std::unique_ptr<PreparedExpressionSum<B, R>>>> transversers_;
    // What transversers run with: the neighbour lists of their own by cutoff, made at the first run of
    // a cutoff no pair term's list covers, the registered ones' output, and the force field's group names.
    std::vector<std::pair<double, std::shared_ptr<VerletList<B, R>>>> transverserLists_;
    typename B::template Buffer<R> transverserOut_;
    // The list a transverser of that cutoff runs over (engine_transversers.hpp), and whether it is one
    // of the transversers' own, which the run itself adapts.
    struct TransverserList {
        std::shared_ptr<VerletList<B, R>> list;
        bool own = false;
    };
    TransverserList transverser_list(double cutoff);
    // Runs a registered transverser into transverserOut_ (engine_transversers.hpp).
    void run_registered_transverser(const TransverserCall& call);
    std::vector<std::string> groupNames_;
    // A spatial domain's slots (hold_ghosts), and the positions version the ghosts were last
    // refreshed at.
    DomainSlots<B, R> domain_{backend_};
    int64_t ghostsAt_ = -1;
};

}  // namespace structmd

#include "simulation/engine_domain.hpp"
#include "simulation/engine_particles.hpp"
#include "simulation/engine_probes.hpp"
#include "simulation/engine_state.hpp"
#include "simulation/engine_transversers.hpp"
