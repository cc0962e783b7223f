// Reading topology.forceField entries: the registry of components this engine knows.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "forcefield/read_forcefield.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;
using input::TrackedNode;

double PairSpec::largest_cutoff() const {
    double largest = 0.0;
    for (const Row& row : rows) largest = std::max(largest, cutOffFactor * row.sigma);
    return largest;
}

namespace {

TrackedNode parameters_of(const ComponentEntry& entry) {
    auto params = entry.node.find("parameters");
    if (!params) return TrackedNode();
    if (!params->is_object()) throw input_error(params->path(), "expected an object of parameters");
    return *params;
}

template <class T>
T parameter(const ComponentEntry& entry, const std::string& key) {
    TrackedNode params = parameters_of(entry);
    if (!params.valid()) throw input_error(entry.node.path() + ".parameters." + key, "missing required parameter");
    return params.get<T>(key);
}

template <class T>
T parameter_or(const ComponentEntry& entry, const std::string& key, T fallback) {
    TrackedNode params = parameters_of(entry);
    return params.valid() ? params.get_or<T>(key, fallback) : fallback;
}

double positive(const TrackedNode& node, double value) {
    if (!(value > 0.0) || !std::isfinite(value)) throw input_error(node.path(), "expected a positive number");
    return value;
}

void read_neighbour_list(const ComponentEntry& entry, const SystemDescription&, ForceFieldSpec& ff) {
    NeighbourListSpec list;
    list.name = entry.name;
    list.path = entry.node.path();
    list.condition = entry.subclass;
    list.verletFactor = parameter_or<double>(entry, "cutOffVerletFactor", 1.1);
    list.minimumCutoff = parameter_or<double>(entry, "cutOff", 0.0);
    if (!(list.verletFactor >= 1.0))
        throw input_error(list.path + ".parameters.cutOffVerletFactor", "expected a number >= 1");
    ff.lists.push_back(list);
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

void read_pair(const ComponentEntry& entry, const SystemDescription& system, ForceFieldSpec& ff) {
    PairSpec pair;
    pair.name = entry.name;
    pair.path = entry.node.path();
    pair.potential = entry.subclass;
    pair.cutOffFactor = parameter<double>(entry, "cutOffFactor");
    positive(parameters_of(entry).at("cutOffFactor"), pair.cutOffFactor);
    pair.shift = parameter_or<bool>(entry, "shift", false);
    pair.condition = parameter<std::string>(entry, "condition");

    const std::string listPath = pair.path + ".parameters.neighbourList";
    if (ff.lists.empty())
        throw input_error(pair.path, "a NonBonded entry needs a [\"VerletConditionalListSet\", condition] entry");
    if (ff.lists.size() > 1 || parameters_of(entry).has("neighbourList")) {
        const std::string wanted = parameter<std::string>(entry, "neighbourList");
        auto it = std::find_if(ff.lists.begin(), ff.lists.end(), [&](const auto& l) { return l.name == wanted; });
        if (it == ff.lists.end()) throw input_error(listPath, "no neighbour list entry named '" + wanted + "'");
        pair.list = static_cast<int>(it - ff.lists.begin());
    }
    const NeighbourListSpec& list = ff.lists[pair.list];
    if (pair.condition != "all" || list.condition != "all")
        throw input_error(pair.path + ".parameters.condition",
                          "condition '" + pair.condition + "' is not available with list '" + list.name +
                              "' of kind '" + list.condition + "' (this version supports \"all\")");

    input::Table table = input::read_table(entry.node, {"name_i", "name_j", "epsilon", "sigma"});
    std::set<std::pair<int, int>> seen;
    for (size_t r = 0; r < table.rows(); ++r) {
        PairSpec::Row row;
        row.typeI = type_of(system, table.cell(r, "name_i"));
        row.typeJ = type_of(system, table.cell(r, "name_j"));
        row.epsilon = table.cell(r, "epsilon").as<double>();
        row.sigma = positive(table.cell(r, "sigma"), table.cell(r, "sigma").as<double>());
        if (!std::isfinite(row.epsilon)) throw input_error(table.cell(r, "epsilon").path(), "expected a finite number");
        const auto key = std::minmax(row.typeI, row.typeJ);
        if (!seen.insert(key).second)
            throw input_error(table.row(r).path(), "type pair listed twice");
        pair.rows.push_back(row);
    }
    const double halfBox = 0.5 * std::min({system.box[0], system.box[1], system.box[2]});
    for (size_t r = 0; r < pair.rows.size(); ++r) {
        const double cutoff = pair.cutOffFactor * pair.rows[r].sigma;
        if (cutoff >= halfBox) {
            std::ostringstream what;
            what << "cutoff " << cutoff << " (cutOffFactor x sigma) is not shorter than half the box (" << halfBox
                 << ")";
            throw input_error(pair.path + ".parameters.cutOffFactor", what.str());
        }
    }
    ff.pairs.push_back(pair);
}

// A bond table: particle-id columns, then a column for each parameter not shared by all bonds;
// the shared ones (the Common_ variants) come from "parameters". Values are stored per bond in the
// order of `parameters`, which is the order the potential's make_params expects.
void read_bonds(const ComponentEntry& entry, const SystemDescription& system, ForceFieldSpec& ff,
                const std::vector<std::string>& parameters, const std::vector<std::string>& common) {
    static const char* const idLabels[] = {"id_i", "id_j", "id_k", "id_l"};
    BondSpec bonds;
    bonds.name = entry.name;
    bonds.path = entry.node.path();
    bonds.potential = entry.subclass;
    bonds.arity = 2;
    bonds.parameterCount = static_cast<int>(parameters.size());

    std::vector<std::string> columns(idLabels, idLabels + bonds.arity);
    std::vector<double> shared(parameters.size(), 0.0);
    std::vector<bool> isShared(parameters.size(), false);
    for (size_t k = 0; k < parameters.size(); ++k) {
        isShared[k] = std::find(common.begin(), common.end(), parameters[k]) != common.end();
        if (isShared[k]) shared[k] = parameter<double>(entry, parameters[k]);
        else columns.push_back(parameters[k]);
    }
    input::Table table = input::read_table(entry.node, columns);
    for (size_t r = 0; r < table.rows(); ++r) {
        for (int k = 0; k < bonds.arity; ++k) {
            const TrackedNode cell = table.cell(r, idLabels[k]);
            const int64_t id = cell.as<int64_t>();
            if (id < 0 || id >= system.numParticles())
                throw input_error(cell.path(), "particle id " + std::to_string(id) + " does not exist");
            for (int m = 0; m < k; ++m)
                if (bonds.ends[bonds.ends.size() - k + m] == id)
                    throw input_error(cell.path(), "particle id " + std::to_string(id) + " appears twice in one bond");
            bonds.ends.push_back(static_cast<int>(id));
        }
        for (size_t k = 0; k < parameters.size(); ++k) {
            if (isShared[k]) {
                bonds.params.push_back(shared[k]);
                continue;
            }
            const TrackedNode cell = table.cell(r, parameters[k]);
            const double value = cell.as<double>();
            if (!std::isfinite(value)) throw input_error(cell.path(), "expected a finite number");
            bonds.params.push_back(value);
        }
    }
    ff.bonds.push_back(bonds);
}

using Reader = std::function<void(const ComponentEntry&, const SystemDescription&, ForceFieldSpec&)>;

Reader bond_reader(std::vector<std::string> parameters, std::vector<std::string> common) {
    return [parameters, common](const ComponentEntry& e, const SystemDescription& s, ForceFieldSpec& ff) {
        read_bonds(e, s, ff, parameters, common);
    };
}

const std::map<std::pair<std::string, std::string>, Reader>& registry() {
    static const std::map<std::pair<std::string, std::string>, Reader> readers = {
        {{"NonBonded", "LennardJonesType1"}, read_pair},
        {{"Bond2", "Harmonic"}, bond_reader({"K", "r0"}, {})},
        {{"Bond2", "HarmonicCommon_K"}, bond_reader({"K", "r0"}, {"K"})},
        {{"Bond2", "HarmonicCommon_K_r0"}, bond_reader({"K", "r0"}, {"K", "r0"})},
        {{"Bond2", "Fene"}, bond_reader({"r0", "K", "R0"}, {})},
        {{"Bond2", "FeneCommon_K_R0"}, bond_reader({"r0", "K", "R0"}, {"K", "R0"})},
        {{"Bond2", "FeneCommon_r0_K_R0"}, bond_reader({"r0", "K", "R0"}, {"r0", "K", "R0"})},
    };
    return readers;
}

}  // namespace

ForceFieldSpec read_forcefield(const SystemDescription& system, const Logger& log) {
    ForceFieldSpec ff;
    // Lists first: a pair entry may name a list that appears after it in the document.
    for (const ComponentEntry& entry : system.forceField) {
        if (entry.cls != "VerletConditionalListSet") continue;
        if (entry.subclass != "all")
            throw input_error(entry.node.path() + ".type",
                              "unknown neighbour list condition '" + entry.subclass + "' (this version knows \"all\")");
        read_neighbour_list(entry, system, ff);
    }
    for (const ComponentEntry& entry : system.forceField) {
        if (entry.cls == "VerletConditionalListSet") continue;
        auto it = registry().find({entry.cls, entry.subclass});
        if (it == registry().end()) {
            std::string known;
            for (const auto& [key, reader] : registry()) known += "\n  [\"" + key.first + "\", \"" + key.second + "\"]";
            throw input_error(entry.node.path() + ".type", "unknown component [\"" + entry.cls + "\", \"" +
                                                              entry.subclass + "\"]; known components:" + known);
        }
        it->second(entry, system, ff);
        ff.entryNames.push_back(entry.name);
    }
    for (const PairSpec& pair : ff.pairs) {
        const int ntypes = static_cast<int>(system.types.size());
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
    return ff;
}

}  // namespace structmd
