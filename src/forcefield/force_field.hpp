#pragma once
// The force field of an engine: its neighbour lists and interactors, evaluated together.
#include <algorithm>
#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "forcefield/interactor.hpp"
#include "neighbour/verlet_list.hpp"
#include "state/drift_bookkeeping.hpp"

namespace structmd {

template <class B, class R>
class ForceField {
public:
    void add(std::unique_ptr<Interactor<B, R>> interactor) { interactors_.push_back(std::move(interactor)); }
    // A group's membership bytes on the backend, shared by every interactor acting on it.
    void add_group(const B& backend, const std::vector<uint8_t>& members) {
        groups_->emplace_back();
        backend.upload(groups_->back(), members.data(), members.size());
    }
    const uint8_t* group(int index) const { return (*groups_)[index].data(); }
    // Uses the group buffers of `other` (a force field made again with new parameters keeps the
    // groups, and so the group pointers integrators hold stay valid).
    void share_groups(const ForceField& other) { groups_ = other.groups_; }
    void add_list(std::shared_ptr<VerletList<B, R>> list) { lists_.push_back(std::move(list)); }
    // Of the pair terms' lists that offer every pair closer than `cutoff` (VerletList::
    // offers_every_pair_within), the one of the smallest cutoff; null if none does.
    std::shared_ptr<VerletList<B, R>> list_offering_every_pair_within(double cutoff, const int* batch) const {
        std::shared_ptr<VerletList<B, R>> best;
        for (const auto& list : lists_)
            if (list->offers_every_pair_within(cutoff, batch) && (!best || list->cutoff() < best->cutoff()))
                best = list;
        return best;
    }
    // A list over sites that terms place themselves (patches): kept up to date and grown as the
    // particles' lists are, but its skin does not limit a step's moves (its sites also turn with their
    // particles, and its own refresh test sees every move).
    void add_site_list(std::shared_ptr<VerletList<B, R>> list) { siteLists_.push_back(std::move(list)); }

    int find(const std::string& name) const {
        for (size_t k = 0; k < interactors_.size(); ++k)
            if (interactors_[k]->name() == name) return static_cast<int>(k);
        return -1;
    }
    const Interactor<B, R>& interactor(int index) const { return *interactors_[index]; }
    std::vector<std::string> names() const {
        std::vector<std::string> all;
        for (const auto& it : interactors_) all.push_back(it->name());
        return all;
    }

    // The longest reach of the neighbour lists (cutoff and skin); 0 without any.
    double largest_list_radius() const {
        double radius = 0.0;
        for (const auto& list : lists_) radius = std::max(radius, list->cutoff() + list->skin());
        return radius;
    }
    // Each list sized for as many neighbours a particle as the same list of `grown` (a force field made
    // from the same spec, for other slots of the same system) came to need, so a new one does not
    // start from its estimate again.
    void reserve_lists_like(const ForceField& grown) {
        for (size_t k = 0; k < lists_.size() && k < grown.lists_.size(); ++k)
            lists_[k]->reserve(grown.lists_[k]->capacity());
        for (size_t k = 0; k < siteLists_.size() && k < grown.siteLists_.size(); ++k)
            siteLists_[k]->reserve(grown.siteLists_[k]->capacity());
    }
    // The thinnest skin of the lists (infinite without lists): no particle may move farther in a step.
    double smallest_skin() const {
        double skin = std::numeric_limits<double>::infinity();
        for (const auto& list : lists_) skin = std::min(skin, list->skin());
        return skin;
    }

    // Prepares the terms active now: only their neighbour lists are kept up to date.
    void prepare(Particles<B, R>& p) {
        for (auto& it : interactors_)
            if (it->active(p.timeline.evaluating_step())) it->prepare(p);
    }
    // The share of a drift's bookkeeping (state/drift_bookkeeping.hpp) of the first list over the
    // particles' positions: its position copy and displacement check. The other lists, if any, keep
    // their own.
    void mirror_in_drift(DriftBookkeeping<R>& drift, const Particles<B, R>& p) {
        mirrored_ = nullptr;
        for (const auto& list : lists_)
            if (const int* slots = list->slot_of(p.pos.data(), p.count)) {
                drift.slotOf = slots;
                drift.slots = p.count;
                drift.mirror = list->mirror();
                mirrored_ = list.get();
                return;
            }
    }
    void drift_mirrored(int64_t version, bool withPositions) {
        if (mirrored_) mirrored_->mirrored(version, withPositions);
    }
    void invalidate_lists() {
        for (auto* lists : {&lists_, &siteLists_})
            for (auto& list : *lists) list->invalidate();
    }
    void adapt() {
        for (auto* lists : {&lists_, &siteLists_})
            for (auto& list : *lists) list->adapt();
    }
    // Builds of every list, as of the last adapt().
    int64_t builds() const {
        int64_t total = 0;
        for (const auto* lists : {&lists_, &siteLists_})
            for (const auto& list : *lists) total += list->builds();
        return total;
    }
    // Adds the terms active at the particles' step; an inactive term costs nothing. out.storeForce
    // goes to the first of them alone (the one first_term_stores_forces names).
    void compute_all(Particles<B, R>& p, const ForceOutputs<R>& out) {
        ForceOutputs<R> outputs = out;
        for (auto& it : interactors_)
            if (it->active(p.timeline.evaluating_step())) {
                it->compute(p, outputs);
                outputs.storeForce = 0;
            }
    }
    // Whether the first term active at the particles' step stores the forces (Interactor::stores_forces).
    bool first_term_stores_forces(const Particles<B, R>& p) const {
        for (const auto& it : interactors_)
            if (it->active(p.timeline.evaluating_step())) return it->stores_forces();
        return false;
    }
    // Adds only the active non-bonded pair terms.
    void compute_pairwise(Particles<B, R>& p, const ForceOutputs<R>& out) {
        for (auto& it : interactors_)
            if (it->pairwise() && it->active(p.timeline.evaluating_step())) {
                it->prepare(p);
                it->compute(p, out);
            }
    }
    // Adds the magnetic field of the active terms that make one (out.magneticField), and nothing else.
    void compute_magnetic_field(Particles<B, R>& p, const ForceOutputs<R>& out) {
        for (auto& it : interactors_)
            if (it->makes_magnetic_field() && it->active(p.timeline.evaluating_step())) {
                it->prepare(p);
                it->compute(p, out);
            }
    }
    void compute_one(int index, Particles<B, R>& p, const ForceOutputs<R>& out) {
        Interactor<B, R>& it = *interactors_[index];
        if (!it.active(p.timeline.evaluating_step())) return;
        it.prepare(p);
        it.compute(p, out);
    }

    bool couples_to_lambda() const {
        for (const auto& it : interactors_)
            if (it->couples_to_lambda()) return true;
        return false;
    }
    // Adds the active terms' dU/dlambda to perParticle (by particle).
    void add_lambda_derivative(Particles<B, R>& p, R* perParticle) {
        for (auto& it : interactors_)
            if (it->couples_to_lambda() && it->active(p.timeline.evaluating_step())) {
                it->prepare(p);
                it->add_lambda_derivative(p, perParticle);
            }
    }

    // The first term without second derivatives (empty when every term has them).
    std::string term_without_hessian() const {
        for (const auto& it : interactors_)
            if (!it->has_hessian()) return it->name();
        return {};
    }
    // The first term that cannot split its forces between pairs (empty when every term can).
    std::string term_without_pair_forces() const {
        for (const auto& it : interactors_)
            if (!it->has_pair_forces()) return it->name();
        return {};
    }
    // Adds the forces each particle exerts on particle `seed` through the active terms to out.
    void add_pair_forces(Particles<B, R>& p, int seed, Real4<R>* out) {
        for (auto& it : interactors_)
            if (it->active(p.timeline.evaluating_step())) {
                it->prepare(p);
                it->add_pair_forces(p, seed, out);
            }
    }
    // Adds the active terms' shares of the Hessian column of particle `seed` to blocks.
    void add_hessian(Particles<B, R>& p, int seed, Tensor3<R>* blocks) {
        for (auto& it : interactors_)
            if (it->active(p.timeline.evaluating_step())) {
                it->prepare(p);
                it->add_hessian(p, seed, blocks);
            }
    }

private:
    std::vector<std::shared_ptr<VerletList<B, R>>> lists_;
    std::vector<std::shared_ptr<VerletList<B, R>>> siteLists_;
    VerletList<B, R>* mirrored_ = nullptr;  // the list the last armed drift keeps (mirror_in_drift)
    std::vector<std::unique_ptr<Interactor<B, R>>> interactors_;
    // deque: buffers never move once made; shared with a force field made again from this one.
    std::shared_ptr<std::deque<typename B::template Buffer<uint8_t>>> groups_ =
        std::make_shared<std::deque<typename B::template Buffer<uint8_t>>>();
};

}  // namespace structmd
