#pragma once
// What is current: forces, per-particle energies and virials, each tagged with the positions
// version (Particles::version) it was computed at. evaluate() brings the stale ones up to date in
// one pass over the force field, so nothing is computed twice and energies and virials only when
// someone asks.
#include <cstdint>

#include "forcefield/force_field.hpp"
#include "simulation/callback_term.hpp"
#include "simulation/engine_functors.hpp"
#include "simulation/simulation.hpp"

namespace structmd {

template <class B, class R>
class ForceCache {
public:
    // flags: ComputeFlags. Counts each evaluated quantity in `counters`. The host's callbacks are
    // part of the pass: called first (so a failing one leaves everything stale), their forces added.
    void evaluate(unsigned flags, const B& backend, Particles<B, R>& p, ForceField<B, R>& forceField,
                  CallbackTerm<B, R>& callbacks, Counters& counters) {
        ForceOutputs<R> out;
        const bool forces = (flags & kForces) && forces_ != p.version;
        bool clearForces = false;
        if (forces) {
            clearForces = cleared_ != p.version;
            cleared_ = kStale;  // a second try at these positions starts from zero again
            out.force = p.force.data();
            // Torques, where kept, go with the forces: the same pass makes both.
            if (!p.torque.empty()) {
                backend.fill(p.torque, Real4<R>{R(0), R(0), R(0), R(0)});
                out.torque = p.torque.data();
            }
        }
        if ((flags & kEnergy) && energy_ != p.version) {
            backend.resize(p.energy, p.count);
            backend.fill(p.energy, R(0));
            out.energy = p.energy.data();
        }
        if ((flags & kVirial) && virial_ != p.version) {
            backend.resize(p.virial, p.count);
            backend.fill(p.virial, zero_tensor<R>());
            out.virial = p.virial.data();
        }
        if (!out.force && !out.energy && !out.virial) return;
        callbacks.evaluate(backend, p);
        forceField.prepare(p);
        if (clearForces) {
            const Real4<R>* external = p.externalForce.empty() ? nullptr : p.externalForce.data();
            if (forceField.first_term_stores_forces(p)) {
                out.storeForce = 1;
                out.forceBase = external;
            } else {
                backend.for_each(p.count, InitForces<R>{p.force.data(), external});
            }
        }
        forceField.compute_all(p, out);
        if (out.force && !callbacks.empty()) callbacks.add_forces(backend, p);
        count(out, counters);
        if (out.force) forces_ = p.version;
        if (out.energy) energy_ = p.version;
        if (out.virial) virial_ = p.version;
    }

    // The buffers were overwritten with something else (one term, the pair terms only).
    void energy_overwritten() { energy_ = kStale; }
    void virial_overwritten() { virial_ = kStale; }
    // Whether the forces are those of these positions.
    bool forces_current(int64_t version) const { return forces_ == version; }
    // Whether the force buffer holds, for these positions, the forces or the external forces a drift
    // kernel cleared it to: either way a change of the external forces is made in it in place.
    bool holds_external_forces(int64_t version) const { return forces_ == version || cleared_ == version; }
    // The drift kernel that made the positions of `version` cleared the forces on its way
    // (state/drift_bookkeeping.hpp): their evaluation there starts without clearing them.
    void forces_cleared(int64_t version) { cleared_ = version; }
    // The external forces changed: forces must be computed again at the same positions.
    void forces_changed() { forces_ = cleared_ = kStale; }
    void invalidate() { forces_ = energy_ = virial_ = cleared_ = kStale; }
    // The slots were renumbered with the forces (a spatial domain's rebuild in place) and the
    // positions, as they were at `before`, are now `after`: forces current before stay current
    // (an integrator that moved the particles after its last evaluation left them stale); energies
    // and virials, not renumbered, are stale.
    void renumbered(int64_t before, int64_t after) {
        const bool current = forces_ == before;
        invalidate();
        if (current) forces_ = after;
    }

    static void count(const ForceOutputs<R>& out, Counters& counters) {
        counters.forceEvaluations += out.force != nullptr;
        counters.energyEvaluations += out.energy != nullptr;
        counters.virialEvaluations += out.virial != nullptr;
    }

private:
    static constexpr int64_t kStale = -1;
    int64_t forces_ = kStale;
    int64_t energy_ = kStale;
    int64_t virial_ = kStale;
    int64_t cleared_ = kStale;  // the version whose forces a drift kernel cleared
};

}  // namespace structmd
