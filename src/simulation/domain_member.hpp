#pragma once
// What a view over MPI ranks (parallel/) needs of the engine it holds, beyond the Simulation
// interface: who fires its simulation steps, and, for a spatial domain, its slots and ghosts
// (domain_exchange.hpp). Only engines implement it (LocalEngine).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "simulation/domain_exchange.hpp"

namespace structmd {

class SimulationStep;  // steps/simulation_step.hpp

// Fires the simulation steps due at the present step. By default an engine fires them on itself;
// one that holds a share of the batches fires them on the whole system instead.
class StepFiring {
public:
    virtual ~StepFiring() = default;
    virtual void fire(const std::vector<SimulationStep*>& due) = 0;
};

class DomainMember {
public:
    virtual ~DomainMember() = default;

    // Who fires the due simulation steps from now on; nullptr: the engine, on itself.
    virtual void set_step_firing(StepFiring* firing) = 0;
    // Moves the simulation steps into `into`, for a view that fires them itself (a spatial domain's,
    // whose engines come and go); the engine has none after.
    virtual void take_steps(std::vector<std::unique_ptr<SimulationStep>>& into) = 0;
    // How far the pair terms' neighbour lists reach (cutoff and skin, the largest of them; 0 without
    // lists), and the largest pair cutoff: a spatial domain's ghost width and move limit follow.
    virtual double list_radius() const = 0;
    virtual double pair_cutoff() const = 0;

    // Makes this engine the domain's as `layout` says: `exchange` refreshes the ghosts before force
    // evaluations (it outlives the engine's use of it), and `begun` says that the schedule's present
    // integrator already began on the domain's previous engine (its state, half-step velocities, is
    // in the particles).
    virtual void hold_ghosts(const DomainLayout& layout, GhostExchange* exchange, bool begun) = 0;
    // The largest distance any owned slot moved since its domain was laid out, reduced where the
    // particles live.
    virtual double largest_owned_move() = 0;
    // A rebuild in place, in three calls (the view moves what they return between ranks in
    // between): sort_owned finds where each owned particle goes; place_owned makes the slots that
    // stay and the arrivals (with their attributes) the owned ones and returns, by link, the
    // global ids of those it sends as ghosts; place_ghosts takes the ghosts' ids and attributes,
    // makes the integrators of `terms` again over the new slots (and its force field, where an
    // array the force field holds had to move), and refreshes the ghosts before the next evaluation.
    virtual SlabSort sort_owned(const SlabGeometry& geometry) = 0;
    virtual std::vector<std::vector<int64_t>> place_owned(const std::vector<Migrant>& arrivals,
                                                          const SlotAttributes& attributes) = 0;
    virtual void place_ghosts(const std::vector<int64_t>& ghostIds, const SlotAttributes& attributes,
                              const DomainTerms& terms) = 0;
    // Each slot's global id, owned slots first.
    virtual std::vector<int64_t> global_ids() = 0;
};

}  // namespace structmd
