#pragma once
// The input document of one spatial domain's engine (domains_over_ranks.hpp): the whole system's
// document with only the domain's particles, its owned ones first and its ghosts after, numbered by
// slot. Rows that name particles are kept with their ids turned into slots (topology.structure,
// state, the id_i/id_j columns of Bond2 entries: a bond is kept when the domain owns one of its
// particles); the simulation steps are left out (the view fires the whole system's, made once).
//
// What domain decomposition does not support yet is refused when the document is read, each by its
// JSON path: STRUCTMD_ERR_UNSUPPORTED "<path>: <what> is not available under domain decomposition".
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace structmd {

class DomainDocument {
public:
    // Checks what the domains support and indexes the rows by particle id.
    explicit DomainDocument(nlohmann::json document);

    int64_t particle_count() const { return static_cast<int64_t>(structureRow_.size()); }
    // The ids bonded to particle `id` (by Bond2 entries).
    const std::vector<int64_t>& bonded_to(int64_t id) const { return partners_[static_cast<size_t>(id)]; }

    // The domain's document: ids[slot] the global id of each slot, the first `owned` of them owned;
    // positions and velocities 3 per slot; the state at `step` and `time`, `remaining` steps before
    // the end of the schedule (an engine's schedule starts at its document's step).
    std::string local_text(const std::vector<int64_t>& ids, int64_t owned, const std::vector<double>& positions,
                           const std::vector<double>& velocities, int64_t step, double time, int64_t remaining) const;

private:
    struct BondTable {
        std::string name;  // its key in topology.forceField
        int columnI = 0, columnJ = 0;
    };

    nlohmann::json skeleton_;  // the document with its particle rows and steps taken out
    nlohmann::json structure_;  // the rows of topology.structure, as given
    int structureIdColumn_ = 0;
    std::vector<size_t> structureRow_;  // by id
    std::vector<BondTable> bondTables_;
    std::vector<nlohmann::json> bondRows_;  // by table, as given
    std::vector<std::vector<std::pair<int, size_t>>> bondsOf_;  // by id: (table, row) of its bonds
    std::vector<std::vector<int64_t>> partners_;
};

}  // namespace structmd
