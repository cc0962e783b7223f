#include "parallel/domain_spec.hpp"

#include <algorithm>
#include <unordered_map>

#include "core/parameters.hpp"

namespace structmd {

namespace {

// The rows of `all` at `ids` (nothing when the whole system has none).
template <class T>
std::vector<T> select(const std::vector<T>& all, const std::vector<int64_t>& ids) {
    std::vector<T> rows;
    if (all.empty()) return rows;
    rows.reserve(ids.size());
    for (int64_t id : ids) rows.push_back(all[static_cast<size_t>(id)]);
    return rows;
}

}  // namespace

DomainSpec::DomainSpec(SystemSpec whole) : whole_(std::move(whole)) {
    const auto n = static_cast<size_t>(particle_count());
    bondsOf_.resize(n);
    partners_.resize(n);
    for (size_t t = 0; t < whole_.forceField.bonds.size(); ++t) {
        const BondSpec& term = whole_.forceField.bonds[t];
        const auto arity = static_cast<size_t>(term.arity);
        for (size_t b = 0; b < term.members.size() / arity; ++b) {
            const auto first = term.members.begin() + static_cast<std::ptrdiff_t>(arity * b);
            std::vector<int> members(first, first + static_cast<std::ptrdiff_t>(arity));
            for (int id : members)
                for (int other : members)
                    if (other != id) partners_[static_cast<size_t>(id)].push_back(other);
            std::sort(members.begin(), members.end());
            members.erase(std::unique(members.begin(), members.end()), members.end());
            for (int id : members) bondsOf_[static_cast<size_t>(id)].emplace_back(static_cast<int>(t), static_cast<int>(b));
        }
    }
}

bool DomainSpec::renumbers_in_place() const {
    const ForceFieldSpec& field = whole_.forceField;
    for (const BondSpec& term : field.bonds)
        if (!term.members.empty()) return false;
    for (const NeighbourListSpec& list : field.lists)
        if (!list.filterInputs.excluded.empty() || !list.filterInputs.kind.empty() || !list.filterInputs.charged.empty())
            return false;
    return field.groups.empty() && std::all_of(whole_.batchId.begin(), whole_.batchId.end(), [](int b) { return b == 0; });
}

SimulationSpec DomainSpec::local(const std::vector<int64_t>& ids, int64_t owned, const std::vector<double>& positions,
                                 const std::vector<double>& velocities, int64_t step, double time,
                                 int64_t remaining) const {
    std::unordered_map<int64_t, int> slotOf;
    slotOf.reserve(ids.size());
    for (size_t slot = 0; slot < ids.size(); ++slot) slotOf[ids[slot]] = static_cast<int>(slot);

    SimulationSpec spec;
    SystemSpec& s = spec;
    s.seed = whole_.seed;
    s.constants = whole_.constants;
    s.velocityKT = whole_.velocityKT;
    s.box = whole_.box;
    s.lambda = whole_.lambda;
    s.currentStep = step;
    s.simulationTime = time;
    s.typeNames = whole_.typeNames;
    s.positions.resize(ids.size());
    s.velocities.resize(ids.size());
    for (size_t slot = 0; slot < ids.size(); ++slot)
        for (int d = 0; d < 3; ++d) {
            s.positions[slot][d] = positions[3 * slot + d];
            s.velocities[slot][d] = velocities[3 * slot + d];
        }
    s.typeIndex = select(whole_.typeIndex, ids);
    s.mass = select(whole_.mass, ids);
    s.radius = select(whole_.radius, ids);
    s.charge = select(whole_.charge, ids);
    s.orientations = select(whole_.orientations, ids);
    s.magnetizations = select(whole_.magnetizations, ids);
    for_each_state_column([&](StateColumn c) { s.columns[c] = select(whole_.columns[c], ids); });
    s.batchId = select(whole_.batchId, ids);
    s.modelId = select(whole_.modelId, ids);

    const ForceFieldSpec& all = whole_.forceField;
    ForceFieldSpec& field = s.forceField;
    field.pairs = all.pairs;
    field.externals = all.externals;
    field.entryNames = all.entryNames;
    for (const GroupSpec& group : all.groups) field.groups.push_back({group.name, select(group.members, ids)});
    for (const NeighbourListSpec& list : all.lists) {
        NeighbourListSpec mine = list;
        mine.filterInputs.kind = select(list.filterInputs.kind, ids);
        mine.filterInputs.charged = select(list.filterInputs.charged, ids);
        mine.filterInputs.excluded.clear();
        if (!list.filterInputs.excluded.empty())
            for (int64_t id : ids) {
                std::vector<int> slots;
                for (int other : list.filterInputs.excluded[static_cast<size_t>(id)])
                    if (const auto it = slotOf.find(other); it != slotOf.end()) slots.push_back(it->second);
                std::sort(slots.begin(), slots.end());
                mine.filterInputs.excluded.push_back(std::move(slots));
            }
        field.lists.push_back(std::move(mine));
    }
    // A bond is kept once when the domain owns one of its particles; the others are then ghosts or
    // owned (the domains check that before they build).
    std::vector<std::vector<int>> kept(all.bonds.size());
    for (int64_t slot = 0; slot < owned; ++slot)
        for (const auto& [term, bond] : bondsOf_[static_cast<size_t>(ids[static_cast<size_t>(slot)])])
            kept[static_cast<size_t>(term)].push_back(bond);
    for (size_t t = 0; t < all.bonds.size(); ++t) {
        const BondSpec& term = all.bonds[t];
        BondSpec mine = term;
        mine.members.clear();
        mine.values.clear();
        std::sort(kept[t].begin(), kept[t].end());
        kept[t].erase(std::unique(kept[t].begin(), kept[t].end()), kept[t].end());
        const auto arity = static_cast<size_t>(term.arity);
        const size_t width = width_of(term.schema);
        for (int bond : kept[t]) {
            const auto b = static_cast<size_t>(bond);
            for (size_t k = 0; k < arity; ++k) mine.members.push_back(slotOf.at(term.members[arity * b + k]));
            mine.values.insert(mine.values.end(), term.values.begin() + width * b, term.values.begin() + width * (b + 1));
        }
        field.bonds.push_back(std::move(mine));
    }

    s.integrators = whole_.integrators;
    s.schedule = whole_.schedule;
    for (ScheduleStage& stage : s.schedule) stage.steps = remaining;
    return spec;
}

}  // namespace structmd
