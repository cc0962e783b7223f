#pragma once
// The simulation as the API layer and the simulation steps see it: one interface, whatever the
// backend and precision behind it (Engine<Backend, Real> implements it). Vectors are 3n doubles in
// particle-id order.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/thermodynamics.hpp"
#include "simulation/domain_exchange.hpp"
#include "simulation/force_callbacks.hpp"

namespace structmd {

struct RuntimeSpec;           // simulation/read_simulation.hpp
class ForceFieldComponents;  // forcefield/component_set.hpp
class SimulationStep;        // steps/simulation_step.hpp

// Fires the simulation steps due at the present step. By default a simulation fires them on itself;
// one that holds a share of the batches (parallel/) fires them on the whole system instead.
class StepFiring {
public:
    virtual ~StepFiring() = default;
    virtual void fire(const std::vector<SimulationStep*>& due) = 0;
};

enum ComputeFlags : unsigned { kForces = 1u, kEnergy = 2u, kVirial = 4u };

// What the engine has done since the simulation was loaded: passes over the force field that
// evaluated forces, energies or the virial, neighbour-list builds, and bytes moved between the
// host and the backend's buffers.
struct Counters {
    uint64_t forceEvaluations = 0;
    uint64_t energyEvaluations = 0;
    uint64_t virialEvaluations = 0;
    uint64_t neighbourListBuilds = 0;
    uint64_t hostToDeviceBytes = 0;
    uint64_t deviceToHostBytes = 0;
    int64_t deviceMemoryBytes = 0;  // held now, not accumulated
    uint64_t stepGraphsCaptured = 0;  // CUDA graphs of steps made, and launches of ones made before
    uint64_t stepGraphsReplayed = 0;
    uint64_t domainRebuilds = 0;  // a system split in space: how often its domains were rebuilt
};

class Simulation {
public:
    virtual ~Simulation() = default;

    virtual int64_t particle_count() const = 0;
    // The particles of mass > 0: under inertial dynamics only they move (held_fixed), so only they
    // carry degrees of freedom.
    virtual int64_t massive_count() const = 0;
    virtual int64_t current_step() const = 0;
    virtual double current_time() const = 0;
    virtual int64_t final_step() const = 0;  // where the schedule ends
    virtual double boltzmann() const = 0;
    virtual std::array<double, 3> box() const = 0;
    virtual double volume() const = 0;

    // Advances n steps along the schedule, firing the simulation steps (past its end, its last
    // integrator goes on); fewer when a flow-control step asks to stop.
    virtual void advance(int64_t n) = 0;
    // Asked by a flow-control step (AFMMaxForce, an escape time with stopSimulation): the step call
    // in progress ends once the simulation steps of the present step number have fired. `by` names it.
    virtual void request_stop(const std::string& by) = 0;
    // The step that ended the last step call early; empty when it ran all its steps.
    virtual const std::string& stopped_by() const = 0;
    // Who fires the due simulation steps from now on; nullptr: the simulation, on itself.
    virtual void set_step_firing(StepFiring* firing) = 0;
    virtual void compute(unsigned flags) = 0;
    // A spatial domain's engine (simulation/domain_exchange.hpp). hold_ghosts makes this engine the
    // domain's as `layout` says: `exchange` refreshes the ghosts before force evaluations (it
    // outlives the engine's use of it), and `begun` says that the schedule's present integrator
    // already began on the domain's previous engine (its state, half-step velocities, is in the
    // particles). Only engines implement these.
    virtual void hold_ghosts(const DomainLayout& /*layout*/, GhostExchange* /*exchange*/, bool /*begun*/) {
        domain_only();
    }
    // The largest distance any owned slot moved since its domain was laid out, reduced where the
    // particles live.
    virtual double largest_owned_move() { domain_only(); }
    // A rebuild in place, in three calls (the view moves what they return between ranks in
    // between): sort_owned finds where each owned particle goes; place_owned makes the slots that
    // stay and the arrivals (with their attributes) the owned ones and returns, by link, the
    // global ids of those it sends as ghosts; place_ghosts takes the ghosts' ids and attributes,
    // makes the integrators of `terms` again over the new slots (and its force field, where an
    // array the force field holds had to move), and refreshes the ghosts before the next evaluation.
    virtual SlabSort sort_owned(const SlabGeometry& /*geometry*/) { domain_only(); }
    virtual std::vector<std::vector<int64_t>> place_owned(const std::vector<Migrant>& /*arrivals*/,
                                                          const SlotAttributes& /*attributes*/) {
        domain_only();
    }
    virtual void place_ghosts(const std::vector<int64_t>& /*ghostIds*/, const SlotAttributes& /*attributes*/,
                              const DomainTerms& /*terms*/) {
        domain_only();
    }
    // Each slot's global id, owned slots first.
    virtual std::vector<int64_t> global_ids() { domain_only(); }
    // Moves the simulation steps into `into`, for a view that fires them itself (a spatial domain's,
    // whose engines come and go); the simulation has none after. Only engines implement it.
    virtual void take_steps(std::vector<std::unique_ptr<SimulationStep>>& /*into*/) {
        throw Error(STRUCTMD_ERR_INTERNAL, "only an engine hands over its simulation steps");
    }
    // How far the pair terms' neighbour lists reach (cutoff and skin, the largest of them; 0 without
    // lists), and the largest pair cutoff: a spatial domain's ghost width and move limit follow.
    virtual double list_radius() const { throw Error(STRUCTMD_ERR_INTERNAL, "only an engine has neighbour lists"); }
    virtual double pair_cutoff() const { throw Error(STRUCTMD_ERR_INTERNAL, "only an engine has neighbour lists"); }

    virtual void get_positions(double* xyz) = 0;  // wrapped into the box
    // Box crossings since the positions were set (3n); unwrapped = wrapped + image L.
    virtual void get_images(int32_t* images) = 0;
    virtual void get_unwrapped_positions(double* xyz) = 0;
    virtual void get_velocities(double* v) = 0;
    virtual void get_forces(double* f) = 0;
    virtual void get_particle_energies(double* e) = 0;
    virtual void get_masses(double* m) = 0;
    virtual void get_types(int32_t* types) = 0;
    virtual void get_radii(double* r) = 0;
    // Orientations as unit quaternions [q0, q1, q2, q3] (4n); [1, 0, 0, 0] for a simulation without
    // any. Setting them (each checked to be of unit norm by the caller) keeps them from then on.
    virtual void get_orientations(double* q) = 0;
    virtual void set_orientations(const double* q) = 0;
    // The torque on each particle (3n, lab frame) at the present state; kept, and evaluated with
    // the forces, from the first call on.
    virtual void get_torques(double* t) = 0;
    // Each particle's magnetic moment in the lab frame (3n): its magnitude times its body-frame
    // direction turned by the orientation; zero for a simulation without magnetization.
    virtual void get_magnetic_moments(double* m) = 0;
    virtual bool has_magnetization() const = 0;
    virtual const std::vector<std::string>& type_names() const = 0;

    // Energy terms: "potential", "kinetic", "total", "external", or a forceField entry name; an
    // unknown term throws ERR_ARGUMENT.
    virtual double energy(const std::string& term) = 0;
    virtual std::vector<std::string> energy_terms() const = 0;  // the forceField entry names
    // One forceField entry's energy on each particle (split as get_particle_energies splits it), its
    // force on each (3n) and its torque on each (3n, lab frame; zero for terms that do not act on
    // orientations), in id order; zero while the entry is inactive. ERR_ARGUMENT for a name that is
    // not an entry.
    virtual void term_energies_and_forces(const std::string& term, double* energies, double* forces,
                                          double* torques) = 0;
    virtual std::array<double, 9> virial() = 0;
    // Per-particle virial of the non-bonded pair terms, 1/2 sum_j (-r_ij) (x) F_ij, row-major (9n).
    virtual void get_pair_virials(double* w) = 0;

    // The Hessian of the force field's potential energy (its terms only: no external forces, no
    // callbacks), one column of 3x3 blocks at a time: for particle `id`, blocks[9 j + 3 a + b] =
    // d2U / dx_id^a dx_j^b for every particle j, in id order. Exact second derivatives; only for an
    // input whose steps ask for them (SimulationStep::needs_hessian), else ERR_STATE.
    virtual void hessian_column(int64_t id, double* blocks) = 0;
    // The forces each particle j exerts on particle `id` through the force field's terms (as
    // hessian_column), 3n in id order: pair forces, and bonds split into central pair forces; fields
    // and tethers of one particle exert none. Only for an input whose steps ask for them
    // (SimulationStep::needs_pair_forces), else ERR_STATE.
    virtual void pair_forces_on(int64_t id, double* f) = 0;
    // The forces of the force field's terms alone (as hessian_column) with particle `id` displaced by
    // `displacement`, in id order (3n); the state is as it was afterwards.
    virtual void forces_with_displaced(int64_t id, const double displacement[3], double* f) = 0;

    virtual void set_positions(const double* xyz) = 0;
    virtual void set_velocities(const double* v) = 0;
    virtual void set_box(const double lengths[3]) = 0;
    virtual void set_external_forces(const double* f) = 0;  // nullptr clears (the energy too)

    // The ensemble's coupling parameter lambda (["Ensemble","NVTlambda"]; 1 under NVT), which the
    // terms of lambda read on the backend. set_lambda takes a value in [0, 1] (ERR_ARGUMENT
    // otherwise) and costs one small kernel, no synchronisation: simulation steps call it between steps.
    virtual double lambda() const = 0;
    virtual void set_lambda(double lambda) = 0;
    // dU/dlambda summed over the active terms of lambda (0 without any).
    virtual double lambda_derivative() = 0;

    // Subsets by id: ids[0..m) are valid and distinct (the API layer checks), values are 3m doubles
    // in the order of ids. Only m entries move between the host and the backend. The setters
    // behave as the whole-array ones for those particles; set_external_forces_of makes a zero field
    // first when there is none.
    virtual void get_positions_of(const int64_t* ids, int64_t m, double* xyz) = 0;
    virtual void get_velocities_of(const int64_t* ids, int64_t m, double* v) = 0;
    virtual void get_forces_of(const int64_t* ids, int64_t m, double* f) = 0;
    virtual void set_positions_of(const int64_t* ids, int64_t m, const double* xyz) = 0;
    virtual void set_velocities_of(const int64_t* ids, int64_t m, const double* v) = 0;
    virtual void set_external_forces_of(const int64_t* ids, int64_t m, const double* f) = 0;

    // The energy of the host's external field, as the host gave it: the energy term "external",
    // part of "total" and of the thermodynamic outputs.
    virtual void set_external_energy(double energy) = 0;
    virtual double external_energy() const = 0;

    // The host's force callbacks (an empty function clears one): called once per configuration at
    // force evaluations; their forces are added, their energy is the term "callback" (part of the
    // whole system's "potential"), their virial part of virial(). A callback that throws (ERR_CALLBACK)
    // inside advance() rolls the state back to the call's start.
    virtual void set_force_callback(HostForceCallback callback) = 0;
    virtual void set_device_force_callback(DeviceForceCallback callback) = 0;

    // The backend's own array of a quantity ("positions", "velocities", "forces"), n Real4 records in
    // id order, with the backend's work finished. Throws ERR_ARGUMENT for another name.
    struct ArrayView {
        const void* data;
        int64_t n;
        int realSize;  // bytes of one real
        int device;    // the CUDA device, or -1 for host memory
    };
    virtual ArrayView view(const std::string& quantity) = 0;

    // Makes the force field and the integrators again from `spec` (the loaded input read again with
    // a parameter changed), keeping the particles, step, time, external forces and the integrators'
    // own state. Everything new is built before anything is replaced: on failure nothing changed.
    // Throws ERR_ARGUMENT when a cutoff would not fit the present box.
    virtual void change_parameters(const RuntimeSpec& spec, const ForceFieldComponents& components) = 0;

    // The dynamic state (step, time, box, positions, images, velocities, external forces, integrator
    // state) to a file, and back into a simulation loaded from the same input. Loading validates
    // the whole file before changing anything.
    virtual void save_checkpoint(const std::string& path) = 0;
    virtual void load_checkpoint(const std::string& path) = 0;

    virtual Counters counters() = 0;

    virtual std::string backend_name() const = 0;
    virtual std::string precision_name() const = 0;
    virtual std::string device_name() const = 0;
    virtual int threads() const = 0;

    // k_B T of the heat bath while the integrator of the next step is overdamped (Brownian dynamics:
    // positions only); empty under inertial dynamics.
    virtual std::optional<double> overdamped_kT() const = 0;

    // The kinetic energy, temperature and pressure as the dynamics defines them. Inertial: K from the
    // velocities, T = 2K / (3 N k_B) with N the particles of mass > 0, P = (2K + tr W) / (3V). Overdamped: no momenta, so K = 0; the
    // temperature is the bath's and the pressure's ideal part N k_B T / V uses it.
    struct Thermodynamics {
        double kinetic = 0.0;
        double temperature = 0.0;
        double virialTrace = 0.0;
        double pressure = 0.0;
    };
    Thermodynamics thermodynamics() {
        Thermodynamics t;
        const std::array<double, 9> w = virial();
        t.virialTrace = w[0] + w[4] + w[8];
        if (const std::optional<double> kT = overdamped_kT()) {
            t.temperature = *kT / boltzmann();
            t.pressure = (static_cast<double>(particle_count()) * *kT + t.virialTrace / 3.0) / volume();
        } else {
            t.kinetic = energy("kinetic");
            t.temperature = kinetic_temperature(t.kinetic, massive_count(), boltzmann());
            t.pressure = virial_pressure(t.kinetic, t.virialTrace, volume());
        }
        return t;
    }
    double pressure() { return thermodynamics().pressure; }

private:
    [[noreturn]] static void domain_only() {
        throw Error(STRUCTMD_ERR_INTERNAL, "only an engine holds the slots of a spatial domain");
    }
};

}  // namespace structmd
