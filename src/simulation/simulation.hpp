#pragma once
// The simulation as the C API and the simulation steps see it: one interface, whatever the backend,
// precision or spread over ranks behind it. An engine (engine.hpp, through LocalEngine) implements
// it, and so do the views over MPI ranks (parallel/), which forward what they do not change
// (forwarding_simulation.hpp). Per-particle arrays go through one keyed accessor (per_particle.hpp);
// what simulation steps probe beyond the state is SimulationProbes (probes()). Vectors are 3n
// doubles in particle-id order.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/thermodynamics.hpp"
#include "simulation/force_callbacks.hpp"
#include "simulation/per_particle.hpp"
#include "simulation/simulation_probes.hpp"

namespace structmd {

struct RuntimeSpec;           // simulation/read_simulation.hpp
class ForceFieldComponents;  // forcefield/component_set.hpp

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
    uint64_t stepsJoined = 0;     // steps that left their end to the next (Integrator::join_steps)
};

// Where the simulation is along its schedule.
struct ScheduleClock {
    int64_t step = 0;
    double time = 0.0;
    int64_t finalStep = 0;  // where the schedule ends
};

// What runs the simulation, for structmd_get_info and the log.
struct EngineDescription {
    std::string backend, precision, device;
    int threads = 0;
};

// A host force callback or a device one; an empty function clears the callback of its kind.
using ForceCallback = std::variant<HostForceCallback, DeviceForceCallback>;

class Simulation {
public:
    virtual ~Simulation() = default;

    virtual int64_t particle_count() const = 0;
    // The particles of mass > 0: under inertial dynamics only they move (held_fixed), so only they
    // carry degrees of freedom.
    virtual int64_t massive_count() const = 0;
    virtual ScheduleClock clock() const = 0;
    virtual double boltzmann() const = 0;
    virtual std::array<double, 3> box() const = 0;
    virtual const std::vector<std::string>& type_names() const = 0;
    // k_B T of the heat bath while the integrator of the next step is overdamped (Brownian dynamics:
    // positions only); empty under inertial dynamics.
    virtual std::optional<double> overdamped_kT() const = 0;
    virtual EngineDescription description() const = 0;
    virtual Counters counters() = 0;

    // Advances n steps along the schedule, firing the simulation steps (past its end, its last
    // integrator goes on); fewer when a flow-control step asks to stop.
    virtual void advance(int64_t n) = 0;
    // Asked by a flow-control step (AFMMaxForce, an escape time with stopSimulation): the step call
    // in progress ends once the simulation steps of the present step number have fired. `by` names it.
    virtual void request_stop(const std::string& by) = 0;
    // The step that ended the last step call early; empty when it ran all its steps.
    virtual const std::string& stopped_by() const = 0;
    virtual void compute(unsigned flags) = 0;

    // A per-particle quantity of every particle (traits(q).width values each, id order). Which
    // quantities each call takes is the C API's (engine_particles.hpp: another is an internal
    // error); a getter that fails leaves `out` alone. Writing positions wraps them and makes everything computed from them stale;
    // writing orientations keeps them from then on; writing external forces with a null array
    // clears them and their energy.
    virtual void read(PerParticle q, double* out) = 0;
    virtual void write(PerParticle q, const double* in) = 0;
    // The same for the particles ids[0..m), valid and distinct (the API layer checks), values in
    // the order of ids; only m entries move between the host and the backend. Writing external
    // forces of a subset makes a zero field first when there is none.
    virtual void read_of(PerParticle q, const int64_t* ids, int64_t m, double* out) = 0;
    virtual void write_of(PerParticle q, const int64_t* ids, int64_t m, const double* in) = 0;

    // The backend's own array of a quantity ("positions", "velocities", "forces"), n Real4 records in
    // id order, with the backend's work finished. Throws ERR_ARGUMENT for another name.
    struct ArrayView {
        const void* data;
        int64_t n;
        int realSize;  // bytes of one real
        int device;    // the CUDA device, or -1 for host memory
    };
    virtual ArrayView view(const std::string& quantity) = 0;

    // Energy terms: "potential", "kinetic", "total", "external" (the host's field, as it gave it),
    // "callback", or a forceField entry name; an unknown term throws ERR_ARGUMENT.
    virtual double energy(const std::string& term) = 0;
    virtual std::vector<std::string> energy_terms() const = 0;  // the forceField entry names
    virtual std::array<double, 9> virial() = 0;
    // The energy of the host's external field: the energy term "external", part of "total" and of
    // the thermodynamic outputs.
    virtual void set_external_energy(double energy) = 0;

    virtual void set_box(const double lengths[3]) = 0;
    // The ensemble's coupling parameter lambda (["Ensemble","NVTlambda"]; 1 under NVT), which the
    // terms of lambda read on the backend. set_lambda takes a value in [0, 1] (ERR_ARGUMENT
    // otherwise) and costs one small kernel, no synchronisation: simulation steps call it between steps.
    virtual double lambda() const = 0;
    virtual void set_lambda(double lambda) = 0;

    // The host's force callbacks: called once per configuration at force evaluations; their forces
    // are added, their energy is the term "callback" (part of the whole system's "potential"),
    // their virial part of virial(). A callback that throws (ERR_CALLBACK) inside advance() rolls
    // the state back to the call's start.
    virtual void set_force_callback(ForceCallback callback) = 0;

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

    // What simulation steps probe beyond the state (Hessian columns, pair forces, lambda).
    virtual SimulationProbes& probes() = 0;

    // Shorthands of the above.
    int64_t current_step() const { return clock().step; }
    double current_time() const { return clock().time; }
    int64_t final_step() const { return clock().finalStep; }
    double volume() const {
        const std::array<double, 3> l = box();
        return l[0] * l[1] * l[2];
    }
    void get_positions(double* xyz) { read(PerParticle::positions, xyz); }
    void get_unwrapped_positions(double* xyz) { read(PerParticle::unwrappedPositions, xyz); }
    void get_velocities(double* v) { read(PerParticle::velocities, v); }
    void get_forces(double* f) { read(PerParticle::forces, f); }
    void get_masses(double* m) { read(PerParticle::masses, m); }
    void get_radii(double* r) { read(PerParticle::radii, r); }
    void get_orientations(double* q) { read(PerParticle::orientations, q); }
    void get_magnetic_moments(double* m) { read(PerParticle::magneticMoments, m); }
    void get_pair_virials(double* w) { read(PerParticle::pairVirials, w); }
    void get_types(int32_t* types);    // the types read as doubles, handed over as integers
    void get_images(int32_t* images);  // the same for the images
    void get_positions_of(const int64_t* ids, int64_t m, double* xyz) { read_of(PerParticle::positions, ids, m, xyz); }
    void get_forces_of(const int64_t* ids, int64_t m, double* f) { read_of(PerParticle::forces, ids, m, f); }

    // The kinetic energy, temperature and pressure as the dynamics defines them. Inertial: K from the
    // velocities, T = 2K / (3 N k_B) with N the particles of mass > 0, P = (2K + tr W) / (3V). Overdamped: no momenta, so K = 0; the
    // temperature is the bath's and the pressure's ideal part N k_B T / V uses it.
    struct Thermodynamics {
        double kinetic = 0.0;
        double temperature = 0.0;
        double virialTrace = 0.0;
        double pressure = 0.0;
    };
    Thermodynamics thermodynamics();
    double pressure() { return thermodynamics().pressure; }
};

}  // namespace structmd
