#pragma once
// An integrator advances the particles by one step; it asks the engine for forces (and, for a
// minimiser, energies) at the positions it needs them, and the engine evaluates only what is stale.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/logger.hpp"
#include "core/parameters.hpp"
#include "core/state_columns.hpp"
#include "state/particles.hpp"

namespace structmd {

class ForceSource {
public:
    virtual ~ForceSource() = default;
    // Makes the force array current for the present positions.
    virtual void update_forces() = 0;
    // The potential energy at the present positions (a reduction: the host waits for it).
    virtual double potential_energy() = 0;
    // Tells the engine the integrator moved the particles to the next step's positions, `elapsed`
    // time later (terms active at that step and fields at that time then apply). driftBookkept: the
    // kernel that moved them applied Particles::drift, as update_forces left it, to every particle.
    virtual void positions_moved(double elapsed, bool driftBookkept) = 0;
    // Makes Particles::magneticField the field at each particle for the present positions,
    // orientations and moments (the magnetic integrators; never cached).
    virtual void update_magnetic_field() = 0;
    // Tells the engine an integrator turned the magnetic moments: what was computed from them is stale.
    virtual void magnetization_changed() = 0;
};

// The particle moved by d, wrapped into the box (its image counts the crossings); the type in w
// stays. The image, in memory, is read and written only on a step that crosses the box, which
// few particles do: 24 bytes a particle-step less for every integrator's drift.
template <class R>
SMD_HD SMD_INLINE Real4<R> displaced(Real4<R> p, const Vec3<R>& d, const Box<R>& box, Image& image) {
    Image crossed{0, 0, 0};
    const Vec3<R> r = box.wrap(Vec3<R>{p.x + d.x, p.y + d.y, p.z + d.z}, crossed);
    if (crossed.x != 0 || crossed.y != 0 || crossed.z != 0) image = Box<R>::images_added(image, crossed);
    p.x = r.x;
    p.y = r.y;
    p.z = r.z;
    return p;
}

// A particle of mass 0 has no inertia to integrate: the inertial integrators (velocity Verlet, the
// Langevin ones) hold it fixed, position and velocity, as OpenMM does; its forces still act on the
// others. Overdamped and minimising integrators do not read the mass.
template <class R>
SMD_HD SMD_INLINE bool held_fixed(const Real4<R>& v) {
    return !(v.w > R(0));
}

// Half a kick: v += dt/2 F/m (the mass rides in v.w); a negative dt kicks back.
template <class R>
SMD_HD SMD_INLINE Real4<R> half_kick(Real4<R> v, const Real4<R>& f, R dt) {
    const R halfDtOverM = R(0.5) * dt / v.w;
    v.x += halfDtOverM * f.x;
    v.y += halfDtOverM * f.y;
    v.z += halfDtOverM * f.z;
    return v;
}

// The force a kick applies to particle i: the force field's, plus, where an integrator owns forces of
// its own (DPD's and SPH's pair forces, pair_verlet.hpp), those too (extra: null for none).
template <class R>
SMD_HD SMD_INLINE Real4<R> kick_force(const Real4<R>* force, const Real4<R>* extra, int64_t i) {
    if (!extra) return force[i];
    const Real4<R> f = force[i], e = extra[i];
    return {f.x + e.x, f.y + e.y, f.z + e.z, R(0)};
}

// The half kick that closes an inertial step (velocity Verlet, Langevin GJF) also checks the
// particle's new velocity and force, so a blow-up is recorded in the step that produced it at no
// extra pass over memory. Not the position: the drift made it from a finite one (the API takes
// finite positions only) and a velocity checked here, and a move that overflowed is longer than the
// skin (the drift's check) or makes this step's forces non-finite. Not reading it saves a quarter of
// the kernel's bytes.
template <class R>
struct ClosingHalfKick {
    const uint8_t* group;
    Real4<R>* vel;
    const Real4<R>* force;
    R dt;
    FaultSlot fault;
    const Real4<R>* extraForce = nullptr;  // added to force (kick_force); null: none
    SMD_HD void operator()(int64_t i) const {
        if ((group && !group[i]) || held_fixed(vel[i])) return;
        const Real4<R> f = kick_force(force, extraForce, i);
        const Real4<R> v = half_kick(vel[i], f, dt);
        vel[i] = v;
        fault.check_kick(i, v, f);
    }
};

// What an integrator reads from its input entry besides timeStep, temperature and group (which every
// integrator takes): its own parameters, by name, and what it needs of the system. Each integrator
// declares a struct derived from this one beside its class.
struct IntegratorInputs {
    static std::vector<Parameter> parameters() { return {}; }
    // Parameters whose value is a name; the chosen one's index in `supported` is stored among the
    // parameters under the option's name. A null fallback makes the option required.
    static std::vector<TextOption> text_options() { return {}; }
    static constexpr bool minimiser = false;    // moves no time forward: needs no time step
    static constexpr bool needsRadius = false;  // its mobility uses each particle's radius
    static constexpr bool overdamped = false;   // moves positions only: the particles have no velocities
    static constexpr bool rotates = false;      // moves orientations too (by the torques)
    static constexpr bool magnetic = false;     // turns the magnetic moments: the state must give them
    // Couples every particle of its group through one fluid: batches, independent systems, would
    // share it, so an input of several is refused.
    static constexpr bool oneFluid = false;
    // Runs under spatial domains (parallel/domains_over_ranks.hpp): moves each particle by its own
    // force and noise alone, so a domain moves the particles it owns as the whole system would.
    static constexpr bool underDomains = false;
    // A parameter that, non-zero, couples every particle of the group (removing its net motion), and
    // what it does: refused under spatial domains, which see only their own particles.
    static constexpr const char* wholeSystemParameter = nullptr;
    static constexpr const char* wholeSystemEffect = nullptr;
    // A parameter that may be left out when the state gives each particle's value in a column
    // (UAMMD-structured's particle data): its default 0 then means "from the column".
    static constexpr const char* fallbackParameter = nullptr;
    static constexpr StateColumn fallbackColumn = StateColumn::frictionConstant;  // read with fallbackParameter only
    // A parameter that, where given (> 0), stands for every particle's radius: the state's radii are
    // then not needed.
    static constexpr const char* radiusParameter = nullptr;
    // Rejects values the integrator cannot run with (beyond each parameter's own rule).
    static void validate(const ParameterValues&, const std::string&) {}
    // Rejects values that cannot run in the input's box (a spectral grid that could never be held),
    // at the load and at every parameter change rather than at the first step.
    static void validate_in_box(const ParameterValues&, const std::array<double, 3>&, const std::string&) {}
};

// What every integrator is given: its time step, its thermal energy, the particles it moves, and
// its entry's name and the handle's log for what it reports.
struct IntegratorScope {
    double timeStep = 0.0;
    double kT = 0.0;                  // k_B T in energy units
    const uint8_t* group = nullptr;   // backend bytes by particle; null: every particle
    std::string name;
    const Logger* log = nullptr;      // null: it reports nothing
    std::string path;                 // its entry's JSON path, for input it can check only when it starts
};

// An integrator whose grid was made for the box it started with refuses a box changed afterwards (the
// first `axes` lengths of `now` against `start`), naming itself (`component`, as ["Class", "SubClass"])
// and what it keeps of that box.
inline void refuse_changed_box(const IntegratorScope& scope, const double* now, const double* start, int axes,
                               const std::string& component, const std::string& keeps) {
    for (int d = 0; d < axes; ++d)
        if (now[d] != start[d])
            throw Error(STRUCTMD_ERR_UNSUPPORTED,
                        scope.name + ": the box changed; " + component + " " + keeps + " of the box it started with");
}

template <class B, class R>
class Integrator {
public:
    explicit Integrator(const IntegratorScope& scope) : scope_(scope) {}
    virtual ~Integrator() = default;
    double time_step() const { return scope_.timeStep; }
    // The simulation time one step adds (a minimiser adds none).
    virtual double time_advance() const { return scope_.timeStep; }
    // Overdamped dynamics has no velocities, so no kinetic energy: its temperature is the bath's.
    virtual bool overdamped() const { return false; }
    double thermal_energy() const { return scope_.kT; }
    // Called before the first step of each stage of the schedule this integrator runs.
    virtual void begin(Particles<B, R>&, ForceSource&) {}
    virtual void step(Particles<B, R>& particles, ForceSource& forces) = 0;
    // Whether step() can leave its last pass over the particles to the next step's first, when the
    // engine says the next step follows with nothing reading the state in between (join_steps).
    virtual bool joins_steps() const { return false; }
    // Set by the engine before each step: whether the last step left its end to this one, and
    // whether this one may leave its end to the next (never where joins_steps() is false); the last
    // step of a call never leaves its end, so a call ends on a whole state.
    struct StepJoin {
        bool fromLast = false;
        bool toNext = false;
    };
    void join_steps(StepJoin join) { join_ = join; }
    // State the integrator carries between steps beyond the particles (a checkpoint saves it).
    virtual std::vector<double> state() const { return {}; }
    virtual void restore(const std::vector<double>&) {}

protected:
    const IntegratorScope& scope() const { return scope_; }
    StepJoin step_join() const { return join_; }

private:
    IntegratorScope scope_;
    StepJoin join_;
};

}  // namespace structmd
