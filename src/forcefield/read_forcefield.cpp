// Reading topology.forceField entries through the component registry: groups and neighbour lists
// first (other entries name them), then every interaction by the generic reader of its kind.
#include "forcefield/read_forcefield.hpp"

#include <algorithm>
#include <set>
#include <tuple>
#include <sstream>

#include "core/error.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;
using input::TrackedNode;

namespace {

// ["VerletConditionalListSet", condition]: the conditions a pair term on such a list may ask for.
struct NeighbourCondition {
    enum class Reads { nothing, types, typeGroups };
    ComponentKey key;
    std::vector<std::pair<std::string, PairCondition>> conditions;
    bool excludes = false;  // reads an id/id_list table of pairs that never interact
    bool charges = false;   // some condition asks whether particles are charged
    Reads kind = Reads::nothing;
    bool allPairs = false;  // ["NBody", condition]: every pair, no list
};

const Registry<NeighbourCondition>& neighbour_conditions() {
    static const Registry<NeighbourCondition> known = [] {
        using Reads = NeighbourCondition::Reads;
        const std::pair<std::string, PairCondition> intra{"intra", PairCondition::intra},
            inter{"inter", PairCondition::inter}, charged{"charged", PairCondition::charged},
            interCharged{"charged", PairCondition::interCharged};
        Registry<NeighbourCondition> r;
        r.add({{"VerletConditionalListSet", "all"}, {{"all", PairCondition::all}}});
        r.add({{"VerletConditionalListSet", "nonExcluded"}, {{"nonExcluded", PairCondition::all}}, true});
        r.add({{"VerletConditionalListSet", "intra_inter"}, {intra, inter}});
        r.add({{"VerletConditionalListSet", "nonExclIntra_nonExclInter"}, {intra, inter}, true});
        r.add({{"VerletConditionalListSet", "nonExclIntra_nonExclInter_nonExclCharged"}, {intra, inter, charged}, true,
               true});
        // UAMMD-structured registers this one as nonExcIntra_nonExcInter_nonExcInterCharged and
        // documents it with "Excl": both spellings are accepted.
        for (const char* name : {"nonExclIntra_nonExclInter_nonExclInterCharged", "nonExcIntra_nonExcInter_nonExcInterCharged"})
            r.add({{"VerletConditionalListSet", name}, {intra, inter, interCharged}, true, true});
        r.add({{"VerletConditionalListSet", "interDifferentType"}, {{"inter", PairCondition::interDifferentType}}, false,
               false, Reads::types});
        r.add({{"VerletConditionalListSet", "nonExclTypeGroup1Intra_nonExclTypeGroup2Intra_nonExclInter_nonExclNoGroup"},
               {{"typeGroup1Intra", PairCondition::typeGroup1Intra},
                {"typeGroup2Intra", PairCondition::typeGroup2Intra},
                {"inter", PairCondition::typeGroupsInter},
                {"noGroup", PairCondition::noTypeGroup}},
               true, false, Reads::typeGroups});
        // UAMMD's NBody module as a list entry: a pair term naming it visits every pair of its batch.
        r.add({{"NBody", "all"}, {{"all", PairCondition::all}}, false, false, Reads::nothing, true});
        return r;
    }();
    return known;
}

std::string parameter_path(const ComponentEntry& entry, const std::string& key) {
    return entry.node.path() + ".parameters." + key;
}

template <class T>
T parameter_or(const ComponentEntry& entry, const std::string& key, T fallback) {
    const TrackedNode params = input::parameters_of(entry.node);
    return params.valid() ? params.get_or<T>(key, fallback) : fallback;
}

template <class T>
T parameter(const ComponentEntry& entry, const std::string& key) {
    const TrackedNode params = input::parameters_of(entry.node);
    if (!params.valid()) throw input_error(parameter_path(entry, key), "missing required parameter");
    return params.get<T>(key);
}

int64_t checked_id(const SystemDescription& system, const TrackedNode& cell) {
    const int64_t id = cell.as<int64_t>();
    if (id < 0 || id >= system.numParticles())
        throw input_error(cell.path(), "particle id " + std::to_string(id) + " does not exist (ids are 0.." +
                                           std::to_string(system.numParticles() - 1) + ")");
    return id;
}

int type_of(const SystemDescription& system, const TrackedNode& cell) {
    const std::string name = cell.as<std::string>();
    const int id = system.typeId(name);
    if (id < 0) {
        std::string known;
        for (const auto& t : system.types) known += (known.empty() ? "" : ", ") + t.name;
        throw input_error(cell.path(), "unknown type '" + name + "' (types are " + known + ")");
    }
    return id;
}

// startStep, endStep and group, which every interaction entry may give, and what a configurable
// component derived from the entry.
void read_common(const ForceFieldComponent& component, const ComponentEntry& entry, const ForceFieldSpec& ff,
                 InteractionSpec& spec) {
    spec.name = entry.name;
    spec.path = entry.node.path();
    spec.key = {entry.cls, entry.subclass};
    spec.startStep = parameter_or<int64_t>(entry, "startStep", 0);
    spec.endStep = parameter_or<int64_t>(entry, "endStep", std::numeric_limits<int64_t>::max());
    if (spec.endStep < spec.startStep)
        throw input_error(parameter_path(entry, "endStep"), "endStep is before startStep");
    spec.group = group_index(ff.groups, parameter_or<std::string>(entry, "group", "All"), parameter_path(entry, "group"));
    spec.config = component.config;
    for (const TextOption& option : component.textOptions)
        input::choose_text_option(option, parameter_or<std::string>(entry, option.name, option.fallback),
                                  parameter_path(entry, option.name));
}

// ---- groups -----------------------------------------------------------------------------------

void read_groups(const ComponentEntry& entry, const SystemDescription& system, ForceFieldSpec& ff) {
    // UAMMD-structured's generators write an empty parameters object; any key in it is unknown.
    if (const auto parameters = entry.node.find("parameters")) parameters->check_all_used();
    const input::Table table = input::read_table(entry.node, {"name", "type", "selection"});
    const int64_t n = system.numParticles();
    for (size_t r = 0; r < table.rows(); ++r) {
        GroupSpec group;
        group.name = table.cell(r, "name").as<std::string>();
        if (group.name == "All") throw input_error(table.cell(r, "name").path(), "the group 'All' always exists");
        const TrackedNode typeCell = table.cell(r, "type");
        std::string kind = typeCell.as<std::string>();
        const bool negate = kind.rfind("not", 0) == 0;
        if (negate) kind = kind.substr(3);
        const TrackedNode selection = table.cell(r, "selection");
        if (!selection.is_array()) throw input_error(selection.path(), "expected a list");
        std::set<int64_t> chosen;
        std::set<std::pair<int64_t, int64_t>> chosenModelBatch;  // ModelIdsBatchIds: [modelId, batchId] pairs
        const std::vector<int32_t>* column = nullptr;
        if (kind == "ModelIdsBatchIds") {
            for (size_t k = 0; k < selection.size(); ++k) {
                const TrackedNode pair = selection.at(k);
                if (!pair.is_array() || pair.size() != 2)
                    throw input_error(pair.path(), "expected a [modelId, batchId] pair");
                chosenModelBatch.insert({pair.at(0).as<int64_t>(), pair.at(1).as<int64_t>()});
            }
        } else if (kind == "Ids") {
            for (size_t k = 0; k < selection.size(); ++k) chosen.insert(checked_id(system, selection.at(k)));
        } else if (kind == "Types") {
            for (size_t k = 0; k < selection.size(); ++k) chosen.insert(type_of(system, selection.at(k)));
            column = &system.typeIndex;
        } else if (kind == "ModelIds" || kind == "BatchIds") {
            for (size_t k = 0; k < selection.size(); ++k) chosen.insert(selection.at(k).as<int64_t>());
            column = kind == "ModelIds" ? &system.modelId : &system.batchId;
        } else {
            throw input_error(typeCell.path(), "unknown selection '" + typeCell.as<std::string>() +
                                                   "' (expected Ids, notIds, Types, notTypes, ModelIds, "
                                                   "notModelIds, BatchIds, notBatchIds, ModelIdsBatchIds or "
                                                   "notModelIdsBatchIds)");
        }
        group.members.assign(n, 0);
        int64_t count = 0;
        for (int64_t i = 0; i < n; ++i) {
            const bool selected = kind == "ModelIdsBatchIds"
                                      ? chosenModelBatch.count({system.modelId[i], system.batchId[i]}) > 0
                                      : chosen.count(column ? (*column)[i] : i) > 0;
            group.members[i] = selected != negate;
            count += group.members[i];
        }
        if (count == 0) throw input_error(table.row(r).path(), "group '" + group.name + "' selects no particle");
        // Sections share one namespace of groups: a group repeated in another section (as
        // UAMMD-structured's inputs do) must select the same particles.
        const auto same = std::find_if(ff.groups.begin(), ff.groups.end(),
                                       [&](const GroupSpec& g) { return g.name == group.name; });
        if (same == ff.groups.end())
            ff.groups.push_back(std::move(group));
        else if (same->members != group.members)
            throw input_error(table.cell(r, "name").path(),
                              "group '" + group.name + "' is defined twice with different selections");
    }
}

// ---- neighbour lists --------------------------------------------------------------------------

// By particle: 1 or 2 for a type in the entry's typeGroup1 or typeGroup2 (type names), else 0.
std::vector<int> type_groups_of(const ComponentEntry& entry, const SystemDescription& system) {
    std::vector<int> groupOfType(system.types.size(), 0);
    for (int group : {1, 2}) {
        const std::string key = "typeGroup" + std::to_string(group);
        const TrackedNode params = input::parameters_of(entry.node);
        if (!params.valid() || !params.has(key))
            throw input_error(parameter_path(entry, key), "missing required parameter: a list of type names");
        const TrackedNode names = params.at(key);
        if (!names.is_array()) throw input_error(names.path(), "expected a list of type names");
        for (size_t k = 0; k < names.size(); ++k) {
            int& slot = groupOfType[type_of(system, names.at(k))];
            if (slot != 0) throw input_error(names.at(k).path(), "a type can be in one type group only");
            slot = group;
        }
    }
    std::vector<int> groups(system.numParticles());
    for (size_t i = 0; i < groups.size(); ++i) groups[i] = groupOfType[system.typeIndex[i]];
    return groups;
}

void read_neighbour_list(const ComponentEntry& entry, const SystemDescription& system, ForceFieldSpec& ff) {
    NeighbourListSpec list;
    list.name = entry.name;
    list.path = entry.node.path();
    const NeighbourCondition& condition =
        neighbour_conditions().at({entry.cls, entry.subclass}, list.path + ".type", "neighbour list");
    list.key = condition.key;
    list.allPairs = condition.allPairs;
    if (list.allPairs) {
        input::read_parameters(entry.node, {});
        ff.lists.push_back(std::move(list));
        return;
    }
    const ParameterValues values = input::read_parameters(
        entry.node, {with_default(number("cutOffVerletFactor", "1", Must::be_at_least_one), 1.1),
                     with_default(number("cutOff", "length", Must::be_non_negative), 0.0)});
    list.verletFactor = values["cutOffVerletFactor"];
    list.minimumCutoff = values["cutOff"];
    PairFilterInputs& inputs = list.filterInputs;
    if (condition.charges)
        for (double q : system.charge) inputs.charged.push_back(q != 0.0 ? 1 : 0);
    if (condition.kind == NeighbourCondition::Reads::types) inputs.kind = system.typeIndex;
    if (condition.kind == NeighbourCondition::Reads::typeGroups) inputs.kind = type_groups_of(entry, system);
    std::vector<std::vector<int>>& excluded = inputs.excluded;
    if (condition.excludes) excluded.assign(system.numParticles(), {});
    if (condition.excludes && entry.node.has("data")) {
        const input::Table table = input::read_table(entry.node, {"id", "id_list"});
        for (size_t r = 0; r < table.rows(); ++r) {
            const int64_t id = checked_id(system, table.cell(r, "id"));
            const TrackedNode others = table.cell(r, "id_list");
            if (!others.is_array()) throw input_error(others.path(), "expected a list of particle ids");
            for (size_t k = 0; k < others.size(); ++k) {
                const int64_t other = checked_id(system, others.at(k));
                if (other == id) throw input_error(others.at(k).path(), "a particle cannot exclude itself");
                excluded[id].push_back(static_cast<int>(other));
            }
        }
        for (auto& ids : excluded) {
            std::sort(ids.begin(), ids.end());
            ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        }
        for (size_t i = 0; i < excluded.size(); ++i)
            for (int j : excluded[i])
                if (!std::binary_search(excluded[j].begin(), excluded[j].end(), static_cast<int>(i)))
                    throw input_error(list.path + ".data", "exclusions must be symmetric: " + std::to_string(i) +
                                                               " excludes " + std::to_string(j) +
                                                               " but not the reverse");
    }
    ff.lists.push_back(std::move(list));
}

// ---- non-bonded pairs -------------------------------------------------------------------------

void choose_list(const ForceFieldComponent& component, const ComponentEntry& entry, const SystemDescription& system,
                 ForceFieldSpec& ff, PairSpec& pair) {
    if (ff.lists.empty())
        throw input_error(pair.path, "a NonBonded entry needs a [\"VerletConditionalListSet\", condition] or "
                                     "[\"NBody\", \"all\"] entry");
    const TrackedNode params = input::parameters_of(entry.node);
    if (ff.lists.size() > 1 || (params.valid() && params.has("neighbourList"))) {
        const std::string wanted = parameter<std::string>(entry, "neighbourList");
        auto it = std::find_if(ff.lists.begin(), ff.lists.end(), [&](const auto& l) { return l.name == wanted; });
        if (it == ff.lists.end())
            throw input_error(parameter_path(entry, "neighbourList"), "no neighbour list entry named '" + wanted + "'");
        pair.list = static_cast<int>(it - ff.lists.begin());
    }
    const NeighbourListSpec& list = ff.lists[pair.list];
    if (list.allPairs && !component.overAllPairs)
        throw input_error(list.path + ".type", component.key.text() + " (" + pair.path +
                                                   ") runs over Verlet lists only, not over an [\"NBody\", \"all\"] entry");
    if (component.infiniteRange && !list.allPairs)
        throw input_error(list.path + ".type", component.key.text() + " (" + pair.path +
                                                   ") acts at every distance: it runs over an [\"NBody\", \"all\"] "
                                                   "list entry, not a Verlet list");
    if (component.infiniteRange && !(is_open_axis(system.box[0]) && is_open_axis(system.box[1]) &&
                                     is_open_axis(system.box[2])))
        throw input_error(system.boxPath, component.key.text() + " (" + pair.path +
                                              ") acts at every distance, so it needs a box open along every axis "
                                              "(0 or \"inf\"): over a periodic axis the nearest images alone would "
                                              "miss the rest of the periodic sum (use [\"LongRange\", \"Electrostatics\"])");
    const auto& known = neighbour_conditions().find(list.key)->conditions;
    const std::string condition = parameter<std::string>(entry, "condition");
    for (const auto& [name, value] : known)
        if (name == condition) {
            pair.condition = value;
            return;
        }
    std::string names;
    for (const auto& k : known) names += (names.empty() ? "" : ", ") + k.first;
    throw input_error(parameter_path(entry, "condition"), "unknown condition '" + condition + "' for neighbour list '" +
                                                              list.name + "' (its conditions: " + names + ")");
}

// The batches, numbered 0, 1, ... in the order of their batchId, as ForceFieldContext numbers them.
class BatchNumbering {
public:
    explicit BatchNumbering(const SystemDescription& system) : system_(system), ids_(system.batchId) {
        std::sort(ids_.begin(), ids_.end());
        ids_.erase(std::unique(ids_.begin(), ids_.end()), ids_.end());
    }
    // The number of the batchId a table's cell names.
    int of_cell(const TrackedNode& cell) const {
        const int64_t id = cell.as<int64_t>();
        const auto at = std::lower_bound(ids_.begin(), ids_.end(), id);
        if (at == ids_.end() || *at != id) throw input_error(cell.path(), "no particle has batchId " + std::to_string(id));
        return static_cast<int>(at - ids_.begin());
    }
    int of_particle(int64_t i) const {
        return static_cast<int>(std::lower_bound(ids_.begin(), ids_.end(), system_.batchId[i]) - ids_.begin());
    }
    int64_t id(int number) const { return ids_[number]; }

private:
    const SystemDescription& system_;
    std::vector<int32_t> ids_;
};

void read_pair(const ForceFieldComponent& component, const ComponentEntry& entry, const SystemDescription& system,
               ForceFieldSpec& ff) {
    PairSpec pair;
    read_common(component, entry, ff, pair);
    choose_list(component, entry, system, ff, pair);
    std::vector<Parameter> own = component.entryParameters;
    if (component.readsCutOffFactor) own.push_back(number("cutOffFactor", "1", Must::be_positive));
    const ParameterValues values = input::read_parameters(entry.node, own);
    if (component.readsCutOffFactor) pair.cutOffFactor = values["cutOffFactor"];
    pair.shift = parameter_or<bool>(entry, "shift", false);
    if (pair.shift && !component.takesShift)
        throw input_error(parameter_path(entry, "shift"),
                          component.key.text() + " has no shifted form: leave \"shift\" out, or false");
    for (const Parameter& p : component.entryParameters) pair.shared.set(p.name, values.vector(p.name));
    const Constants constants = constants_of(system);
    pair.everyTypePair = component.parameters.empty();
    if (pair.everyTypePair) {
        pair.cutoff = component.actingCutoff(pair.shared, constants, pair.cutOffFactor, pair.shift);
    } else {
        // A batchId column (UAMMD-structured's batched tables) gives each batch its own rows.
        std::vector<std::string> columns = {"name_i", "name_j"};
        for (const Parameter& p : component.parameters) columns.push_back(p.name);
        const input::Table table = input::read_table(entry.node, columns, {"batchId"});
        const bool batched = table.has("batchId");
        const BatchNumbering batches(system);
        std::set<std::tuple<int, int, int>> seen;
        for (size_t r = 0; r < table.rows(); ++r) {
            PairSpec::Row row;
            row.typeI = type_of(system, table.cell(r, "name_i"));
            row.typeJ = type_of(system, table.cell(r, "name_j"));
            if (batched) row.batch = batches.of_cell(table.cell(r, "batchId"));
            for (const Parameter& p : component.parameters)
                row.values.set(p.name, input::read_parameter(table.cell(r, p.name), p));
            if (!seen.insert({row.batch, std::min(row.typeI, row.typeJ), std::max(row.typeI, row.typeJ)}).second)
                throw input_error(table.row(r).path(),
                                  batched ? "type pair listed twice for this batchId" : "type pair listed twice");
            pair.cutoff = std::max(pair.cutoff, component.actingCutoff(pair.values_of(row), constants,
                                                                       pair.cutOffFactor, pair.shift));
            pair.rows.push_back(std::move(row));
        }
        if (component.unlistedCutoff) {
            pair.unlistedPairsInteract = true;
            pair.cutoff = std::max(pair.cutoff,
                                   component.unlistedCutoff(pair.shared, constants, pair.cutOffFactor, pair.shift));
        }
    }
    if (!cutoff_fits_box(pair.cutoff, system.box)) {
        std::ostringstream what;
        what.precision(17);  // a box just below 2 r_c must not print as if it were 2 r_c
        what << "cutoff " << pair.cutoff << " is not shorter than half the box ("
             << half_shortest_edge(system.box[0], system.box[1], system.box[2]) << ")";
        const std::string path = !component.cutoffPath.empty() ? component.cutoffPath
                                 : !component.cutoffKey.empty() ? entry.node.path() + "." + component.cutoffKey
                                 : parameter_path(entry, component.readsCutOffFactor ? "cutOffFactor" : "cutOff");
        throw input_error(path, what.str());
    }
    ff.pairs.push_back(std::move(pair));
}

// ---- bonds ------------------------------------------------------------------------------------

// A bond table: particle-id columns, then a column for each parameter not shared by all bonds;
// the shared ones (the Common_ variants) come from "parameters". Values are stored per bond in the
// order of the component's schema.
void read_bonds(const ForceFieldComponent& component, const ComponentEntry& entry, const SystemDescription& system,
                ForceFieldSpec& ff) {
    static const char* const idLabels[] = {"id_i", "id_j", "id_k", "id_l"};
    BondSpec bonds;
    read_common(component, entry, ff, bonds);
    bonds.arity = component.arity;
    bonds.schema = component.parameters;
    const auto is_common = [&](const Parameter& p) {
        return std::find(component.common.begin(), component.common.end(), p.name) != component.common.end();
    };
    std::vector<Parameter> commonSchema;
    std::vector<std::string> columns(idLabels, idLabels + bonds.arity);
    for (const Parameter& p : bonds.schema) {
        if (is_common(p))
            commonSchema.push_back(p);
        else
            columns.push_back(p.name);
    }
    const ParameterValues shared = input::read_parameters(entry.node, commonSchema);
    const input::Table table = input::read_table(entry.node, columns);
    bonds.values.reserve(table.rows() * width_of(bonds.schema));
    for (size_t r = 0; r < table.rows(); ++r) {
        const size_t first = bonds.members.size();
        for (int k = 0; k < bonds.arity; ++k) {
            const TrackedNode cell = table.cell(r, idLabels[k]);
            const int id = static_cast<int>(checked_id(system, cell));
            for (size_t m = first; m < bonds.members.size(); ++m)
                if (bonds.members[m] == id)
                    throw input_error(cell.path(), "particle id " + std::to_string(id) + " appears twice in one bond");
            bonds.members.push_back(id);
        }
        for (const Parameter& p : bonds.schema) {
            const std::vector<double> numbers =
                is_common(p) ? shared.vector(p.name) : input::read_parameter(table.cell(r, p.name), p);
            bonds.values.insert(bonds.values.end(), numbers.begin(), numbers.end());
        }
    }
    ff.bonds.push_back(std::move(bonds));
}

// ---- external fields --------------------------------------------------------------------------

void read_external(const ForceFieldComponent& component, const ComponentEntry& entry, const SystemDescription& system,
                   ForceFieldSpec& ff) {
    ExternalSpec external;
    read_common(component, entry, ff, external);
    external.values = input::read_parameters(entry.node, component.parameters);
    external.perType = !component.typeParameters.empty();
    if (external.perType) {
        // A batchId column (UAMMD-structured's batched tables) gives each batch its own rows.
        std::vector<std::string> columns = {"name"}, optional = component.ignoredTypeColumns;
        for (const Parameter& p : component.typeParameters) columns.push_back(p.name);
        optional.push_back("batchId");
        const input::Table table = input::read_table(entry.node, columns, optional);
        const bool batched = table.has("batchId");
        const BatchNumbering batches(system);
        std::set<std::pair<int, int>> seen;
        for (size_t r = 0; r < table.rows(); ++r) {
            ExternalSpec::Row row;
            row.type = type_of(system, table.cell(r, "name"));
            if (batched) row.batch = batches.of_cell(table.cell(r, "batchId"));
            for (const Parameter& p : component.typeParameters)
                row.values.set(p.name, input::read_parameter(table.cell(r, p.name), p));
            if (!seen.insert({row.batch, row.type}).second)
                throw input_error(table.row(r).path(),
                                  batched ? "type listed twice for this batchId" : "type listed twice");
            external.rows.push_back(std::move(row));
        }
    }
    ff.externals.push_back(std::move(external));
}

// Type pairs a pair table does not list, and types a per-type external's table does not list, act not.
void warn_unlisted_types(const SystemDescription& system, const ForceFieldSpec& ff, const Logger& log) {
    const int ntypes = static_cast<int>(system.types.size());
    const BatchNumbering batches(system);
    std::set<std::pair<int, int>> present;  // the (batch, type) of each particle
    for (int64_t i = 0; i < system.numParticles(); ++i) present.insert({batches.of_particle(i), system.typeIndex[i]});
    for (const ExternalSpec& external : ff.externals) {
        if (!external.perType) continue;
        for (int a = 0; a < ntypes; ++a)
            if (std::none_of(external.rows.begin(), external.rows.end(),
                             [&](const ExternalSpec::Row& r) { return r.type == a; }))
                log.warning(external.path + ": type " + system.types[a].name + " is not listed and feels nothing");
        // A batched table: the particles of a (batch, type) it does not list feel nothing either.
        if (external.rows.empty() || external.rows.front().batch < 0) continue;
        std::set<std::pair<int, int>> listed;
        for (const ExternalSpec::Row& r : external.rows) listed.insert({r.batch, r.type});
        for (const auto& [batch, type] : present)
            if (!listed.count({batch, type}))
                log.warning(external.path + ": type " + system.types[type].name + " of batchId " +
                            std::to_string(batches.id(batch)) + " is not listed and feels nothing");
    }
    for (const PairSpec& pair : ff.pairs) {
        if (pair.everyTypePair || pair.unlistedPairsInteract) continue;
        if (pair.batched()) {
            // Only the type pairs a batch holds matter, within that batch.
            std::set<std::tuple<int, int, int>> listed;
            for (const PairSpec::Row& r : pair.rows)
                listed.insert({r.batch, std::min(r.typeI, r.typeJ), std::max(r.typeI, r.typeJ)});
            for (const auto& [batch, a] : present)
                for (auto b = present.lower_bound({batch, a}); b != present.end() && b->first == batch; ++b)
                    if (!listed.count({batch, a, b->second}))
                        log.warning(pair.path + ": type pair (" + system.types[a].name + ", " +
                                    system.types[b->second].name + ") of batchId " + std::to_string(batches.id(batch)) +
                                    " is not listed and does not interact");
            continue;
        }
        for (int a = 0; a < ntypes; ++a)
            for (int b = a; b < ntypes; ++b) {
                const bool listed = std::any_of(pair.rows.begin(), pair.rows.end(), [&](const PairSpec::Row& r) {
                    return std::minmax(r.typeI, r.typeJ) == std::minmax(a, b);
                });
                if (!listed)
                    log.warning(pair.path + ": type pair (" + system.types[a].name + ", " + system.types[b].name +
                                ") is not listed and does not interact");
            }
    }
}

}  // namespace

std::vector<ComponentKey> neighbour_list_keys() {
    std::vector<ComponentKey> keys;
    for (const NeighbourCondition& condition : neighbour_conditions().entries()) keys.push_back(condition.key);
    return keys;
}

Constants constants_of(const SystemDescription& system) {
    const double largestRadius =
        system.radius.empty() ? 0.0 : *std::max_element(system.radius.begin(), system.radius.end());
    return {system.units.boltzmann, system.units.electricConversion, largestRadius, system.temperature};
}

ForceFieldSpec read_forcefield(const SystemDescription& system, const Logger& log,
                               const Registry<ForceFieldComponent>& registry) {
    ForceFieldSpec ff;
    const auto read_group_entry = [&](const ComponentEntry& entry) {
        if (entry.subclass != "GroupsList")
            throw input_error(entry.node.path() + ".type", "unknown component [\"Groups\", \"" + entry.subclass +
                                                              "\"] (expected [\"Groups\", \"GroupsList\"])");
        read_groups(entry, system, ff);
    };
    for (const ComponentEntry& entry : system.forceField)
        if (entry.cls == "Groups") read_group_entry(entry);
    for (const ComponentEntry& entry : system.sectionGroups) read_group_entry(entry);
    for (const ComponentEntry& entry : system.forceField)
        if (entry.cls == "VerletConditionalListSet" || entry.cls == "NBody") read_neighbour_list(entry, system, ff);
    for (const ComponentEntry& entry : system.forceField) {
        if (entry.cls == "VerletConditionalListSet" || entry.cls == "NBody" || entry.cls == "Groups") continue;
        const ForceFieldComponent& registered =
            registry.at({entry.cls, entry.subclass}, entry.node.path() + ".type", "component");
        const ForceFieldComponent component = registered.configure ? registered.configure(entry, system) : registered;
        if (!component.units.empty() && component.units != system.units.name)
            throw input_error(entry.node.path() + ".type",
                              component.key.text() + " is defined in " + component.units +
                                  " units only (its constants are numbers in them); the input's units (global.units) are " +
                                  system.units.name);
        if (component.needsMagnetization && system.magnetizations.empty())
            throw input_error(entry.node.path() + ".type",
                              component.key.text() + " acts on magnetic moments: the state needs a 'magnetization' column");
        switch (component.kind) {
            case InteractionKind::pair: read_pair(component, entry, system, ff); break;
            case InteractionKind::bond: read_bonds(component, entry, system, ff); break;
            case InteractionKind::external: read_external(component, entry, system, ff); break;
        }
        ff.entryNames.push_back(entry.name);
    }
    warn_unlisted_types(system, ff, log);
    return ff;
}

}  // namespace structmd
