#pragma once
// What a spatial domain's view (parallel/domains_over_ranks.hpp) and its engine hand each other:
// the engine holds the particles its rank owns in slots [0, owned) and ghosts, copies of particles
// other ranks own, in the slots after them; the view moves data between ranks (MPI, through the
// host), the engine does the per-slot work where the particles live (simulation/domain_slots.hpp).
#include <array>
#include <cstdint>
#include <vector>

#include "core/slab_geometry.hpp"

namespace structmd {

struct ForceFieldSpec;        // forcefield/forcefield_spec.hpp
struct IntegratorSpec;        // integrators/integrator_spec.hpp
class ForceFieldComponents;  // forcefield/component_set.hpp

// Refreshes the ghosts before every force evaluation at new positions: the engine hands the
// positions of its border slots (`bytes` each, in the order the view's links send them) to
// exchange(), which fills its ghost slots' (in slot order) with their owners'. Where the view can
// move them between GPUs directly (NCCL), the engine hands device memory to exchange_on_device()
// instead, with the stream its kernels run on.
class GhostExchange {
public:
    virtual ~GhostExchange() = default;
    virtual void exchange(const void* border, void* ghosts, size_t bytes) = 0;
    virtual bool exchanges_on_device() const { return false; }
    virtual void exchange_on_device(const void* /*border*/, void* /*ghosts*/, size_t /*bytes*/, void* /*stream*/) {}
};

// A particle as it crosses to another domain: its global id, where it is, how fast, its box
// crossings since load, and the force on it at these positions (a rebuild in place keeps the
// forces, so the step after it evaluates them only once the particles moved).
struct Migrant {
    int64_t id = 0;
    std::array<double, 3> position{}, velocity{}, force{};
    std::array<int32_t, 3> image{};
};

// What a domain's engine cannot know of the particles it is given (arrivals, ghosts): one each, from
// the whole system's spec by global id.
struct SlotAttributes {
    std::vector<int32_t> typeIndex, model;
    std::vector<double> mass, radius, charge;
};

// A domain as its engine was made for it: each slot's global id (keys its noise), how many are
// owned (the ghosts follow), the owned particles' images, and the owned slots each link sends as
// ghosts, concatenated in link order.
struct DomainLayout {
    std::vector<int64_t> globalIds;
    int64_t owned = 0;
    std::vector<std::array<int32_t, 3>> images;
    std::vector<int64_t> borderSlots;
};

// The owned slots sorted at a rebuild: how many stay, the particles leaving for the rank above and
// below (SlabGeometry::kUp, kDown), and the largest id of one that strayed farther (-1: none).
struct SlabSort {
    int64_t stay = 0;
    std::vector<Migrant> up, down;
    int64_t astray = -1;
};

// What a rebuild makes again over the new slots: the integrators, and the force field where an array
// it holds had to move (its terms hold nothing by slot: DomainSpec::renumbers_in_place).
struct DomainTerms {
    const ForceFieldSpec* forceField = nullptr;
    const std::vector<IntegratorSpec>* integrators = nullptr;
    const ForceFieldComponents* components = nullptr;
};

}  // namespace structmd
