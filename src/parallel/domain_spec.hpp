#pragma once
// The engine spec of one spatial domain (domains_over_ranks.hpp): the whole system's spec, read once
// at load, with only the domain's particles, its owned ones first and its ghosts after, numbered by
// slot. Per-particle rows are selected; what names particles is renumbered by slot (bond members,
// neighbour-list exclusions, group members); a bond is kept when the domain owns one of its
// particles. Made in memory, so that a rebuild of the domains costs a selection of rows, not a
// document written and read again.
#include <cstdint>
#include <utility>
#include <vector>

#include "simulation/simulation_spec.hpp"

namespace structmd {

class DomainSpec {
public:
    explicit DomainSpec(SystemSpec whole);

    int64_t particle_count() const { return static_cast<int64_t>(whole_.positions.size()); }
    const SystemSpec& whole() const { return whole_; }
    // Whether the domain's terms hold nothing by slot (no bonds, no neighbour-list exclusions or
    // per-particle conditions, no groups, one batch numbered 0), so that a rebuild can renumber the
    // engine's slots in place (Simulation::reseat) instead of making it anew.
    bool renumbers_in_place() const;
    // The ids bonded to particle `id`.
    const std::vector<int64_t>& bonded_to(int64_t id) const { return partners_[static_cast<size_t>(id)]; }

    // The domain's spec: ids[slot] the global id of each slot, the first `owned` of them owned;
    // positions and velocities 3 per slot; at `step` and `time` with `remaining` steps of the
    // schedule left (the domains allow one stage).
    SimulationSpec local(const std::vector<int64_t>& ids, int64_t owned, const std::vector<double>& positions,
                         const std::vector<double>& velocities, int64_t step, double time, int64_t remaining) const;

private:
    SystemSpec whole_;
    std::vector<std::vector<std::pair<int, int>>> bondsOf_;  // by id: (bond term, bond) it takes part in
    std::vector<std::vector<int64_t>> partners_;
};

}  // namespace structmd
