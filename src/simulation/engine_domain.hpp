#pragma once
// Engine as a spatial domain's (DomainMember): its slots, owned then ghosts, laid out, sorted and
// renumbered where the particles live (domain_slots.hpp).
#include <cmath>
#include <vector>

#include "simulation/engine.hpp"

namespace structmd {

template <class B, class R, class PairR>
void Engine<B, R, PairR>::hold_ghosts(const DomainLayout& layout, GhostExchange* exchange, bool begun) {
    backend_.activate();
    domain_.hold(p_, layout, exchange);
    p_.noise.ids = domain_.global_ids();
    ghostsAt_ = p_.version;  // the ghosts were loaded with their owners' present positions
    if (begun && schedule_.stages() > 0) activeStage_ = schedule_.stage_after(current_step());
    cache_.invalidate();
}

template <class B, class R, class PairR>
double Engine<B, R, PairR>::largest_owned_move() {
    backend_.activate();
    return std::sqrt(domain_.largest_owned_move(p_));
}

template <class B, class R, class PairR>
SlabSort Engine<B, R, PairR>::sort_owned(const SlabGeometry& geometry) {
    backend_.activate();
    return domain_.sort_owned(p_, geometry);
}

template <class B, class R, class PairR>
std::vector<std::vector<int64_t>> Engine<B, R, PairR>::place_owned(const std::vector<Migrant>& arrivals,
                                                                   const SlotAttributes& attributes) {
    backend_.activate();
    return domain_.place_owned(arrivals, attributes, p_);
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::place_ghosts(const std::vector<int64_t>& ghostIds, const SlotAttributes& attributes,
                                       const DomainTerms& terms) {
    backend_.activate();
    const int* model = p_.model.data();
    domain_.place_ghosts(p_, ghostIds, attributes);
    p_.noise.ids = domain_.global_ids();
    p_.drift = {};
    context_.particles = p_.count;
    context_.model = p_.model.data();
    // The host's copies by slot are not kept for a domain's slots: its view answers for them.
    host_.typeIndex.clear();
    host_.masses.clear();
    host_.radii.clear();
    host_.batchId.assign(static_cast<size_t>(p_.count), 0);
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

template <class B, class R, class PairR>
std::vector<int64_t> Engine<B, R, PairR>::global_ids() {
    backend_.activate();
    return domain_.ids_on_host(p_.count);
}

}  // namespace structmd
