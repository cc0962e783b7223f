// Reading topology.forceField entries: the registry of components this engine knows.
#include "forcefield/read_forcefield.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "core/error.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;
using input::TrackedNode;

double PairSpec::largest_cutoff() const {
    if (potential == "DebyeHuckel") return cutOffFactor * debyeLength;
    double largest = 0.0;
    for (const Row& row : rows) largest = std::max(largest, cutOffFactor * row.sigma);
    return largest;
}

namespace {

using Reader = std::function<void(const ComponentEntry&, const SystemDescription&, ForceFieldSpec&)>;

TrackedNode parameters_of(const ComponentEntry& entry) {
    auto params = entry.node.find("parameters");
    if (!params) return TrackedNode();
    if (!params->is_object()) throw input_error(params->path(), "expected an object of parameters");
    return *params;
}

std::string parameter_path(const ComponentEntry& entry, const std::string& key) {
    return entry.node.path() + ".parameters." + key;
}

template <class T>
T parameter(const ComponentEntry& entry, const std::string& key) {
    TrackedNode params = parameters_of(entry);
    if (!params.valid()) throw input_error(parameter_path(entry, key), "missing required parameter");
    return params.get<T>(key);
}

template <class T>
T parameter_or(const ComponentEntry& entry, const std::string& key, T fallback) {
    TrackedNode params = parameters_of(entry);
    return params.valid() ? params.get_or<T>(key, fallback) : fallback;
}

double checked_positive(const std::string& path, double value) {
    if (!(value > 0.0) || !std::isfinite(value)) throw input_error(path, "expected a positive number");
    return value;
}

double checked_finite(const std::string& path, double value) {
    if (!std::isfinite(value)) throw input_error(path, "expected a finite number");
    return value;
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

// startStep, endStep and group, which every interaction entry may give.
void read_common(const ComponentEntry& entry, const std::string& family, const ForceFieldSpec& ff,
                 InteractionSpec& spec) {
    spec.name = entry.name;
    spec.path = entry.node.path();
    spec.potential = family;
    spec.startStep = parameter_or<int64_t>(entry, "startStep", 0);
    spec.endStep = parameter_or<int64_t>(entry, "endStep", std::numeric_limits<int64_t>::max());
    if (spec.endStep < spec.startStep)
        throw input_error(parameter_path(entry, "endStep"), "endStep is before startStep");
    const std::string group = parameter_or<std::string>(entry, "group", "All");
    if (group == "All") return;
    auto it = std::find_if(ff.groups.begin(), ff.groups.end(), [&](const GroupSpec& g) { return g.name == group; });
    if (it == ff.groups.end())
        throw input_error(parameter_path(entry, "group"), "no group named '" + group + "' (define it in a "
                                                          "[\"Groups\", \"GroupsList\"] entry)");
    spec.group = static_cast<int>(it - ff.groups.begin());
}

// ---- groups -----------------------------------------------------------------------------------

void read_groups(const ComponentEntry& entry, const SystemDescription& system, ForceFieldSpec& ff) {
    const input::Table table = input::read_table(entry.node, {"name", "type", "selection"});
    const int64_t n = system.numParticles();
    for (size_t r = 0; r < table.rows(); ++r) {
        GroupSpec group;
        group.name = table.cell(r, "name").as<std::string>();
        if (group.name == "All") throw input_error(table.cell(r, "name").path(), "the group 'All' always exists");
        for (const GroupSpec& g : ff.groups)
            if (g.name == group.name) throw input_error(table.cell(r, "name").path(), "group defined twice");
        const TrackedNode typeCell = table.cell(r, "type");
        std::string kind = typeCell.as<std::string>();
        const bool negate = kind.rfind("not", 0) == 0;
        if (negate) kind = kind.substr(3);
        const TrackedNode selection = table.cell(r, "selection");
        if (!selection.is_array()) throw input_error(selection.path(), "expected a list");
        std::set<int64_t> chosen;
        const std::vector<int32_t>* column = nullptr;
        if (kind == "Ids") {
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
                                                   "notModelIds, BatchIds or notBatchIds)");
        }
        group.members.assign(n, 0);
        int64_t count = 0;
        for (int64_t i = 0; i < n; ++i) {
            const bool selected = chosen.count(column ? (*column)[i] : i) > 0;
            group.members[i] = selected != negate;
            count += group.members[i];
        }
        if (count == 0) throw input_error(table.row(r).path(), "group '" + group.name + "' selects no particle");
        ff.groups.push_back(std::move(group));
    }
}

// ---- neighbour lists --------------------------------------------------------------------------

void read_neighbour_list(const ComponentEntry& entry, const SystemDescription& system, ForceFieldSpec& ff) {
    NeighbourListSpec list;
    list.name = entry.name;
    list.path = entry.node.path();
    list.condition = entry.subclass;
    list.verletFactor = parameter_or<double>(entry, "cutOffVerletFactor", 1.1);
    list.minimumCutoff = parameter_or<double>(entry, "cutOff", 0.0);
    if (!(list.verletFactor >= 1.0))
        throw input_error(parameter_path(entry, "cutOffVerletFactor"), "expected a number >= 1");
    if (list.condition == "nonExcluded") list.excluded.assign(system.numParticles(), {});
    if (list.condition == "nonExcluded" && entry.node.has("data")) {
        const input::Table table = input::read_table(entry.node, {"id", "id_list"});
        for (size_t r = 0; r < table.rows(); ++r) {
            const int64_t id = checked_id(system, table.cell(r, "id"));
            const TrackedNode others = table.cell(r, "id_list");
            if (!others.is_array()) throw input_error(others.path(), "expected a list of particle ids");
            for (size_t k = 0; k < others.size(); ++k) {
                const int64_t other = checked_id(system, others.at(k));
                if (other == id) throw input_error(others.at(k).path(), "a particle cannot exclude itself");
                list.excluded[id].push_back(static_cast<int>(other));
            }
        }
        for (auto& ids : list.excluded) {
            std::sort(ids.begin(), ids.end());
            ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        }
        for (size_t i = 0; i < list.excluded.size(); ++i)
            for (int j : list.excluded[i])
                if (!std::binary_search(list.excluded[j].begin(), list.excluded[j].end(), static_cast<int>(i)))
                    throw input_error(list.path + ".data", "exclusions must be symmetric: " + std::to_string(i) +
                                                               " excludes " + std::to_string(j) +
                                                               " but not the reverse");
    }
    ff.lists.push_back(std::move(list));
}

std::vector<std::string> sub_lists(const std::string& condition) {
    if (condition == "intra_inter") return {"intra", "inter"};
    return {condition};
}

// ---- non-bonded pairs -------------------------------------------------------------------------

void choose_list(const ComponentEntry& entry, ForceFieldSpec& ff, PairSpec& pair) {
    if (ff.lists.empty())
        throw input_error(pair.path, "a NonBonded entry needs a [\"VerletConditionalListSet\", condition] entry");
    const TrackedNode params = parameters_of(entry);
    if (ff.lists.size() > 1 || (params.valid() && params.has("neighbourList"))) {
        const std::string wanted = parameter<std::string>(entry, "neighbourList");
        auto it = std::find_if(ff.lists.begin(), ff.lists.end(), [&](const auto& l) { return l.name == wanted; });
        if (it == ff.lists.end())
            throw input_error(parameter_path(entry, "neighbourList"), "no neighbour list entry named '" + wanted + "'");
        pair.list = static_cast<int>(it - ff.lists.begin());
    }
    const NeighbourListSpec& list = ff.lists[pair.list];
    pair.subList = parameter<std::string>(entry, "condition");
    const std::vector<std::string> known = sub_lists(list.condition);
    if (std::find(known.begin(), known.end(), pair.subList) == known.end()) {
        std::string names;
        for (const auto& k : known) names += (names.empty() ? "" : ", ") + k;
        throw input_error(parameter_path(entry, "condition"), "unknown condition '" + pair.subList +
                                                                  "' for neighbour list '" + list.name +
                                                                  "' (its conditions: " + names + ")");
    }
}

void check_cutoff(const ComponentEntry& entry, const SystemDescription& system, const PairSpec& pair) {
    const double halfBox = 0.5 * std::min({system.box[0], system.box[1], system.box[2]});
    const double cutoff = pair.largest_cutoff();
    if (cutoff >= halfBox) {
        std::ostringstream what;
        what.precision(17);  // a box just below 2 r_c must not print as if it were 2 r_c
        what << "cutoff " << cutoff << " is not shorter than half the box (" << halfBox << ")";
        throw input_error(parameter_path(entry, "cutOffFactor"), what.str());
    }
}

Reader pair_reader(const std::string& family) {
    return [family](const ComponentEntry& entry, const SystemDescription& system, ForceFieldSpec& ff) {
        PairSpec pair;
        read_common(entry, family, ff, pair);
        choose_list(entry, ff, pair);
        pair.cutOffFactor = checked_positive(parameter_path(entry, "cutOffFactor"),
                                             parameter<double>(entry, "cutOffFactor"));
        pair.shift = parameter_or<bool>(entry, "shift", false);
        const input::Table table = input::read_table(entry.node, {"name_i", "name_j", "epsilon", "sigma"});
        std::set<std::pair<int, int>> seen;
        for (size_t r = 0; r < table.rows(); ++r) {
            PairSpec::Row row;
            row.typeI = type_of(system, table.cell(r, "name_i"));
            row.typeJ = type_of(system, table.cell(r, "name_j"));
            row.epsilon = checked_finite(table.cell(r, "epsilon").path(), table.cell(r, "epsilon").as<double>());
            row.sigma = checked_positive(table.cell(r, "sigma").path(), table.cell(r, "sigma").as<double>());
            if (!seen.insert(std::minmax(row.typeI, row.typeJ)).second)
                throw input_error(table.row(r).path(), "type pair listed twice");
            pair.rows.push_back(row);
        }
        check_cutoff(entry, system, pair);
        ff.pairs.push_back(std::move(pair));
    };
}

void read_debye_huckel_pair(const ComponentEntry& entry, const SystemDescription& system, ForceFieldSpec& ff) {
    PairSpec pair;
    read_common(entry, "DebyeHuckel", ff, pair);
    choose_list(entry, ff, pair);
    pair.cutOffFactor = checked_positive(parameter_path(entry, "cutOffFactor"), parameter<double>(entry, "cutOffFactor"));
    pair.dielectricConstant = checked_positive(parameter_path(entry, "dielectricConstant"),
                                               parameter<double>(entry, "dielectricConstant"));
    pair.debyeLength = checked_positive(parameter_path(entry, "debyeLength"), parameter<double>(entry, "debyeLength"));
    pair.shift = parameter_or<bool>(entry, "shift", false);
    check_cutoff(entry, system, pair);
    ff.pairs.push_back(std::move(pair));
}

// ---- bonds ------------------------------------------------------------------------------------

// What a parameter's numbers must be, beyond finite.
enum class Must { be_finite, be_positive, be_integer };

// A parameter of a bonded term and how many numbers it holds (3 for a vector).
struct Parameter {
    std::string name;
    int size = 1;
    Must must = Must::be_finite;
};

void read_values(const TrackedNode& node, int size, std::vector<double>& values, Must must = Must::be_finite) {
    if (size == 1) {
        const double value = checked_finite(node.path(), node.as<double>());
        if (must == Must::be_integer && value != std::floor(value)) throw input_error(node.path(), "expected an integer");
        if (must == Must::be_positive) checked_positive(node.path(), value);
        values.push_back(value);
        return;
    }
    if (!node.is_array() || node.size() != static_cast<size_t>(size))
        throw input_error(node.path(), "expected a list of " + std::to_string(size) + " numbers");
    for (int k = 0; k < size; ++k) values.push_back(checked_finite(node.at(k).path(), node.at(k).as<double>()));
}

// A bond table: particle-id columns, then a column for each parameter not shared by all bonds;
// the shared ones (the Common_ variants) come from "parameters". Values are stored per bond in the
// order of `parameters`, which is the order the potential's make_params expects.
Reader bond_reader(std::string family, int arity, std::vector<Parameter> parameters,
                   std::vector<std::string> common = {}) {
    return [=](const ComponentEntry& entry, const SystemDescription& system, ForceFieldSpec& ff) {
        static const char* const idLabels[] = {"id_i", "id_j", "id_k", "id_l"};
        BondSpec bonds;
        read_common(entry, family, ff, bonds);
        bonds.arity = arity;
        std::vector<std::string> columns(idLabels, idLabels + arity);
        std::vector<std::vector<double>> shared(parameters.size());
        for (size_t k = 0; k < parameters.size(); ++k) {
            bonds.parameterCount += parameters[k].size;
            if (std::find(common.begin(), common.end(), parameters[k].name) != common.end()) {
                TrackedNode params = parameters_of(entry);
                if (!params.valid())
                    throw input_error(parameter_path(entry, parameters[k].name), "missing required parameter");
                read_values(params.at(parameters[k].name), parameters[k].size, shared[k], parameters[k].must);
            } else {
                columns.push_back(parameters[k].name);
            }
        }
        const input::Table table = input::read_table(entry.node, columns);
        for (size_t r = 0; r < table.rows(); ++r) {
            const size_t first = bonds.members.size();
            for (int k = 0; k < arity; ++k) {
                const TrackedNode cell = table.cell(r, idLabels[k]);
                const int id = static_cast<int>(checked_id(system, cell));
                for (size_t m = first; m < bonds.members.size(); ++m)
                    if (bonds.members[m] == id)
                        throw input_error(cell.path(), "particle id " + std::to_string(id) + " appears twice in one bond");
                bonds.members.push_back(id);
            }
            for (size_t k = 0; k < parameters.size(); ++k) {
                if (!shared[k].empty())
                    bonds.params.insert(bonds.params.end(), shared[k].begin(), shared[k].end());
                else
                    read_values(table.cell(r, parameters[k].name), parameters[k].size, bonds.params,
                                parameters[k].must);
            }
        }
        ff.bonds.push_back(std::move(bonds));
    };
}

// ---- external fields --------------------------------------------------------------------------

// Parameters of an external potential: name, size, and a default (NaN: required).
struct ExternalParameter {
    std::string name;
    int size;
    double fallback;
    Must must = Must::be_finite;
};

Reader external_reader(std::string family, std::vector<ExternalParameter> parameters) {
    return [=](const ComponentEntry& entry, const SystemDescription&, ForceFieldSpec& ff) {
        ExternalSpec external;
        read_common(entry, family, ff, external);
        TrackedNode params = parameters_of(entry);
        for (const ExternalParameter& p : parameters) {
            auto node = params.valid() ? params.find(p.name) : std::nullopt;
            if (node) {
                read_values(*node, p.size, external.values, p.must);
            } else if (std::isnan(p.fallback)) {
                throw input_error(parameter_path(entry, p.name), "missing required parameter");
            } else {
                external.values.insert(external.values.end(), p.size, p.fallback);
            }
        }
        ff.externals.push_back(std::move(external));
    };
}

// ---- the registry -----------------------------------------------------------------------------

const std::map<std::pair<std::string, std::string>, Reader>& registry() {
    const double required = std::numeric_limits<double>::quiet_NaN();
    const double infinity = std::numeric_limits<double>::infinity();
    static const std::map<std::pair<std::string, std::string>, Reader> readers = [&] {
        std::map<std::pair<std::string, std::string>, Reader> r;
        for (const char* family : {"LennardJonesType1", "LennardJonesType2", "LennardJonesType3", "WCAType1",
                                   "WCAType2", "WCAType3", "GeneralLennardJonesType1", "GeneralLennardJonesType2",
                                   "GeneralLennardJonesType3", "Steric6", "Steric12"})
            r[{"NonBonded", family}] = pair_reader(family);
        r[{"NonBonded", "DebyeHuckel"}] = read_debye_huckel_pair;

        r[{"Bond1", "FixedHarmonic"}] = bond_reader("FixedHarmonic", 1, {{"K"}, {"r0"}, {"position", 3}});
        r[{"Bond1", "ConstantForce"}] = bond_reader("ConstantForce", 1, {{"force", 3}});

        const std::vector<Parameter> harmonic = {{"K"}, {"r0"}};
        r[{"Bond2", "Harmonic"}] = bond_reader("Harmonic", 2, harmonic);
        r[{"Bond2", "HarmonicCommon_K"}] = bond_reader("Harmonic", 2, harmonic, {"K"});
        r[{"Bond2", "HarmonicCommon_K_r0"}] = bond_reader("Harmonic", 2, harmonic, {"K", "r0"});
        const Must positive = Must::be_positive;
        const std::vector<Parameter> fene = {{"r0"}, {"K"}, {"R0", 1, positive}};
        r[{"Bond2", "Fene"}] = bond_reader("Fene", 2, fene);
        r[{"Bond2", "FeneCommon_K_R0"}] = bond_reader("Fene", 2, fene, {"K", "R0"});
        r[{"Bond2", "FeneCommon_r0_K_R0"}] = bond_reader("Fene", 2, fene, {"r0", "K", "R0"});
        const std::vector<Parameter> morse = {{"r0"}, {"E"}, {"D", 1, positive}};
        r[{"Bond2", "Morse"}] = bond_reader("Morse", 2, morse);
        r[{"Bond2", "MorseCommon_D"}] = bond_reader("Morse", 2, morse, {"D"});
        r[{"Bond2", "MorseCommon_r0_E_D"}] = bond_reader("Morse", 2, morse, {"r0", "E", "D"});
        const std::vector<Parameter> lennardJones = {{"epsilon"}, {"sigma"}};
        for (const char* family : {"LennardJonesType1", "LennardJonesType2", "LennardJonesType3"}) {
            r[{"Bond2", family}] = bond_reader(family, 2, lennardJones);
            r[{"Bond2", std::string(family) + "Common_epsilon"}] = bond_reader(family, 2, lennardJones, {"epsilon"});
        }
        const std::vector<Parameter> gaussian = {{"E"}, {"r0"}, {"D", 1, positive}};
        r[{"Bond2", "Gaussian"}] = bond_reader("Gaussian", 2, gaussian);
        r[{"Bond2", "GaussianCommon_E_r0_D"}] = bond_reader("Gaussian", 2, gaussian, {"E", "r0", "D"});
        for (const char* family : {"Steric6", "Steric12"}) {
            r[{"Bond2", family}] = bond_reader(family, 2, lennardJones);
            r[{"Bond2", std::string(family) + "Common_epsilon_sigma"}] =
                bond_reader(family, 2, lennardJones, {"epsilon", "sigma"});
        }
        r[{"Bond2", "DebyeHuckel"}] = bond_reader(
            "DebyeHuckel", 2,
            {{"chgProduct"}, {"dielectricConstant", 1, positive}, {"debyeLength", 1, positive}, {"cutOff", 1, positive}});

        const std::vector<Parameter> angle = {{"K"}, {"theta0"}};
        r[{"Bond3", "HarmonicAngular"}] = bond_reader("HarmonicAngular", 3, angle);
        r[{"Bond3", "HarmonicAngularCommon_K"}] = bond_reader("HarmonicAngular", 3, angle, {"K"});
        r[{"Bond3", "HarmonicAngularCommon_K_theta0"}] = bond_reader("HarmonicAngular", 3, angle, {"K", "theta0"});
        r[{"Bond3", "KratkyPorod"}] = bond_reader("KratkyPorod", 3, {{"K"}});
        r[{"Bond3", "KratkyPorodCommon_K"}] = bond_reader("KratkyPorod", 3, {{"K"}}, {"K"});

        const std::vector<Parameter> dihedral = {{"n", 1, Must::be_integer}, {"K"}, {"phi0"}};
        r[{"Bond4", "Dihedral"}] = bond_reader("Dihedral", 4, dihedral);
        r[{"Bond4", "DihedralCommon_n_K_phi0"}] = bond_reader("Dihedral", 4, dihedral, {"n", "K", "phi0"});
        r[{"Bond4", "Dihedral4"}] = bond_reader("Dihedral4", 4, {{"K", 4}, {"phi0", 4}});

        r[{"External", "ConstantForce"}] = external_reader("ConstantForce", {{"constantForce", 3, required}});
        r[{"External", "Plates"}] = external_reader(
            "Plates", {{"platesSeparation", 1, required, Must::be_positive}, {"platesEpsilon", 1, 1.0}, {"platesSigma", 1, 1.0},
                       {"compressionVelocity", 1, 0.0}, {"minPlatesSeparation", 1, 0.0},
                       {"maxPlatesSeparation", 1, infinity}});
        r[{"External", "SphericalShell"}] = external_reader(
            "SphericalShell", {{"shellCenter", 3, required}, {"shellRadius", 1, required, Must::be_positive}, {"shellEpsilon", 1, 1.0},
                               {"shellSigma", 1, 1.0}, {"minShellRadius", 1, 0.0}, {"maxShellRadius", 1, infinity},
                               {"radiusVelocity", 1, 0.0}});
        return r;
    }();
    return readers;
}

}  // namespace

ForceFieldSpec read_forcefield(const SystemDescription& system, const Logger& log) {
    ForceFieldSpec ff;
    // Groups and lists first: other entries name them, wherever they stand in the document.
    for (const ComponentEntry& entry : system.forceField) {
        if (entry.cls != "Groups") continue;
        if (entry.subclass != "GroupsList")
            throw input_error(entry.node.path() + ".type", "unknown component [\"Groups\", \"" + entry.subclass +
                                                              "\"] (expected [\"Groups\", \"GroupsList\"])");
        read_groups(entry, system, ff);
    }
    for (const ComponentEntry& entry : system.forceField) {
        if (entry.cls != "VerletConditionalListSet") continue;
        if (entry.subclass != "all" && entry.subclass != "nonExcluded" && entry.subclass != "intra_inter")
            throw input_error(entry.node.path() + ".type", "unknown neighbour list condition '" + entry.subclass +
                                                              "' (expected all, nonExcluded or intra_inter)");
        read_neighbour_list(entry, system, ff);
    }
    for (const ComponentEntry& entry : system.forceField) {
        if (entry.cls == "VerletConditionalListSet" || entry.cls == "Groups") continue;
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
        if (pair.potential == "DebyeHuckel") continue;
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
