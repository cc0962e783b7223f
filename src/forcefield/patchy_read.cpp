// Reading ["PatchyParticles","PatchyParticles"] and ["PatchyParticles","DynamicallyBondedPatchyParticles"]:
// the patches (patchesState: id and body-frame position), their types (patchesGlobal.types) and
// fundamental (energyThreshold), their parents (patchesTopology.structure) and their own force field
// (patchesTopology.forceField: one neighbour list and the patch terms), into a PatchyConfig.
#include <array>
#include <cmath>
#include <optional>
#include <set>
#include <string>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/patchy_particles.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;
using input::TrackedNode;

namespace {

// ["Class","SubClass"] of a sub-entry, its "type" marked read.
std::pair<std::string, std::string> type_of_entry(const TrackedNode& entry) {
    const TrackedNode type = entry.at("type");
    if (!type.is_array() || type.size() != 2 || !type.at(size_t{0}).is_string() || !type.at(size_t{1}).is_string())
        throw input_error(type.path(), "expected [\"Class\", \"SubClass\"]");
    return {type.at(size_t{0}).as<std::string>(), type.at(size_t{1}).as<std::string>()};
}

int patch_type(const PatchyConfig& config, const TrackedNode& cell) {
    const std::string name = cell.as<std::string>();
    for (int t = 0; t < config.ntypes(); ++t)
        if (config.typeNames[t] == name) return t;
    std::string known;
    for (const std::string& t : config.typeNames) known += (known.empty() ? "" : ", ") + t;
    throw input_error(cell.path(), "unknown patch type '" + name + "' (patch types are " + known + ")");
}

double read_number(const TrackedNode& cell, const Parameter& p) { return input::read_parameter(cell, p)[0]; }

void read_types(const TrackedNode& global, PatchyConfig& config) {
    const TrackedNode types = global.at("types");
    const auto [cls, subclass] = type_of_entry(types);
    if (cls != "Types" || subclass != "Basic")
        throw input_error(types.path() + ".type", "expected [\"Types\", \"Basic\"]");
    const input::Table table = input::read_table(types, {"name"}, {"mass", "radius", "charge"});
    for (size_t r = 0; r < table.rows(); ++r) {
        const std::string name = table.cell(r, "name").as<std::string>();
        for (const std::string& known : config.typeNames)
            if (known == name) throw input_error(table.cell(r, "name").path(), "patch type '" + name + "' listed twice");
        config.typeNames.push_back(name);
        config.typeRadius.push_back(table.has("radius") ? table.cell(r, "radius").as<double>() : 0.5);
    }
    if (config.typeNames.empty()) throw input_error(types.path() + ".data", "expected at least one patch type");
}

void read_fundamental(const TrackedNode& global, PatchyConfig& config) {
    const auto fundamental = global.find("fundamental");
    if (!fundamental) return;
    const auto [cls, subclass] = type_of_entry(*fundamental);
    if (cls != "Fundamental" || (subclass != "DynamicallyBondedPatchyParticles" && subclass != "None"))
        throw input_error(fundamental->path() + ".type",
                          "expected [\"Fundamental\", \"DynamicallyBondedPatchyParticles\"] or [\"Fundamental\", \"None\"]");
    const ParameterValues values =
        input::read_parameters(*fundamental, {with_default(number("energyThreshold", "energy"), 0.0)});
    config.energyThreshold = values["energyThreshold"];
}

// patchesState and patchesTopology.structure: the same ids, in the same order (as UAMMD-structured asks).
void read_patches(const TrackedNode& entry, const TrackedNode& topology, const SystemDescription& system,
                  PatchyConfig& config) {
    const TrackedNode state = entry.at("patchesState");
    const input::Table positions = input::read_table(state, {"id", "position"});
    const TrackedNode structureNode = topology.at("structure");
    const input::Table structure = input::read_table(structureNode, {"id", "type", "parentId"}, {"batchId"});
    if (positions.rows() != structure.rows())
        throw input_error(structureNode.path() + ".data", "has " + std::to_string(structure.rows()) +
                                                              " patches, patchesState has " +
                                                              std::to_string(positions.rows()));
    for (size_t r = 0; r < positions.rows(); ++r) {
        const TrackedNode idCell = positions.cell(r, "id");
        if (idCell.as<int64_t>() != static_cast<int64_t>(r))
            throw input_error(idCell.path(), "expected patch id " + std::to_string(r) + " (ids run 0, 1, ... in order)");
        if (structure.cell(r, "id").as<int64_t>() != static_cast<int64_t>(r))
            throw input_error(structure.cell(r, "id").path(), "expected patch id " + std::to_string(r) +
                                                                  " (the order of patchesState)");
        const std::array<double, 3> x = positions.cell(r, "position").as<std::array<double, 3>>();
        for (double c : x)
            if (!std::isfinite(c)) throw input_error(positions.cell(r, "position").path(), "expected finite coordinates");
        config.offset.push_back({x[0], x[1], x[2]});
        config.type.push_back(patch_type(config, structure.cell(r, "type")));
        const TrackedNode parentCell = structure.cell(r, "parentId");
        const int64_t parent = parentCell.as<int64_t>();
        if (parent < 0 || parent >= system.numParticles())
            throw input_error(parentCell.path(), "particle id " + std::to_string(parent) + " does not exist (ids are 0.." +
                                                     std::to_string(system.numParticles() - 1) + ")");
        config.parent.push_back(static_cast<int>(parent));
        if (structure.has("batchId")) {
            const TrackedNode batchCell = structure.cell(r, "batchId");
            if (batchCell.as<int64_t>() != system.batchId[parent])
                throw input_error(batchCell.path(), "a patch is in its parent's batch (" +
                                                        std::to_string(system.batchId[parent]) + ")");
        }
    }
}

// The one neighbour list of the patch pair terms: its factor and which conditions it offers.
struct PatchList {
    std::string name, path;
    double verletFactor = 1.1;
    std::vector<std::pair<std::string, PairCondition>> conditions;
};

PatchList read_patch_list(const TrackedNode& node, const std::string& name, const std::string& subclass) {
    PatchList list;
    list.name = name;
    list.path = node.path();
    if (subclass == "all")
        list.conditions = {{"all", PairCondition::all}};
    else if (subclass == "intra_inter")
        list.conditions = {{"intra", PairCondition::intra}, {"inter", PairCondition::inter}};
    else if (subclass == "interDifferentType")
        list.conditions = {{"inter", PairCondition::interDifferentType}};
    else
        throw input_error(node.path() + ".type", "patches take a [\"VerletConditionalListSet\", \"all\"], "
                                                 "\"intra_inter\" or \"interDifferentType\" list, got \"" + subclass + "\"");
    const ParameterValues values =
        input::read_parameters(node, {with_default(number("cutOffVerletFactor", "1", Must::be_at_least_one), 1.1)});
    list.verletFactor = values["cutOffVerletFactor"];
    return list;
}

// A pair term's condition, which the patch list must offer; the same for every pair term of the entry.
void choose_condition(const TrackedNode& node, const PatchList* list, PatchyConfig& config) {
    if (!list) throw input_error(node.path(), "a NonBondedPatches entry needs a [\"VerletConditionalListSet\", "
                                              "condition] entry beside it");
    const std::string path = node.path() + ".parameters.condition";
    const TrackedNode params = input::parameters_of(node);
    if (!params.valid() || !params.has("condition")) throw input_error(path, "missing required parameter");
    const std::string wanted = params.get<std::string>("condition");
    for (const auto& [name, condition] : list->conditions)
        if (name == wanted) {
            if (config.hasPairs && condition != config.condition)
                throw input_error(path, "every NonBondedPatches term of one patchy entry takes the same condition");
            config.condition = condition;
            config.hasPairs = true;
            config.verletFactor = list->verletFactor;
            return;
        }
    std::string names;
    for (const auto& c : list->conditions) names += (names.empty() ? "" : ", ") + c.first;
    throw input_error(path, "unknown condition '" + wanted + "' for neighbour list '" + list->name +
                                "' (its conditions: " + names + ")");
}

void read_cosine(const TrackedNode& node, PatchyConfig& config) {
    const int nt = config.ntypes();
    config.cosine.assign(nt * nt, {0.0, 1.0, 1.0});
    config.cosineListed.assign(nt * nt, 0);
    const input::Table table = input::read_table(node, {"name_i", "name_j", "E", "K", "rc"});
    for (size_t r = 0; r < table.rows(); ++r) {
        const int i = patch_type(config, table.cell(r, "name_i")), j = patch_type(config, table.cell(r, "name_j"));
        if (config.cosineListed[i * nt + j]) throw input_error(table.row(r).path(), "type pair listed twice");
        const DistanceSwitchCosinePatch::Params<double> p{read_number(table.cell(r, "E"), number("E", "energy")),
                                                          read_number(table.cell(r, "K"), number("K", "1", Must::be_positive)),
                                                          read_number(table.cell(r, "rc"), number("rc", "length", Must::be_positive))};
        for (int at : {i * nt + j, j * nt + i}) {
            config.cosine[at] = p;
            config.cosineListed[at] = 1;
        }
        config.cutoff = std::max(config.cutoff, p.rc);
    }
}

// The rotation matrix of a unit quaternion, by columns (as the kernels use it).
patch_math::Frame<double> frame(const Real4<double>& q) { return patch_math::frame_of(q); }

bool transposes(const Real4<double>& a, const Real4<double>& b) {
    const patch_math::Frame<double> A = frame(a), B = frame(b);
    // A^T = B: row k of A is column k of B.
    const Vec3<double> rows[3] = {{A.x.x, A.y.x, A.z.x}, {A.x.y, A.y.y, A.z.y}, {A.x.z, A.y.z, A.z.z}};
    const Vec3<double> cols[3] = {B.x, B.y, B.z};
    for (int k = 0; k < 3; ++k) {
        const Vec3<double> d = rows[k] - cols[k];
        if (std::fabs(d.x) > 1e-6 || std::fabs(d.y) > 1e-6 || std::fabs(d.z) > 1e-6) return false;
    }
    return true;
}

void read_cosrap(const TrackedNode& node, PatchyConfig& config) {
    const int nt = config.ntypes();
    config.cosrap.assign(nt * nt, {0.0, 1.0, 1.0, 1.0, {1.0, 0.0, 0.0, 0.0}});
    config.cosrapListed.assign(nt * nt, 0);
    std::vector<uint8_t> given(nt * nt, 0);
    const input::Table table = input::read_table(node, {"name_i", "name_j", "E", "Kswt", "Krap", "rc", "R"});
    for (size_t r = 0; r < table.rows(); ++r) {
        const int i = patch_type(config, table.cell(r, "name_i")), j = patch_type(config, table.cell(r, "name_j"));
        if (given[i * nt + j]) throw input_error(table.row(r).path(), "type pair listed twice");
        given[i * nt + j] = 1;
        const std::vector<double> q = input::read_parameter(table.cell(r, "R"), numbers("R", 4, "1"));
        const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        if (std::fabs(norm - 1.0) > 1e-5)
            throw input_error(table.cell(r, "R").path(), "expected a unit quaternion [q0, q1, q2, q3], its norm is " +
                                                             std::to_string(norm));
        CosrapPatch::Params<double> p{read_number(table.cell(r, "E"), number("E", "energy")),
                                      read_number(table.cell(r, "Kswt"), number("Kswt", "1", Must::be_positive)),
                                      read_number(table.cell(r, "Krap"), number("Krap", "1", Must::be_positive)),
                                      read_number(table.cell(r, "rc"), number("rc", "length", Must::be_positive)),
                                      {q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm}};
        // (j, i) takes the transposed rotation (the conjugate quaternion); given both ways, they must agree.
        if (i == j && !transposes(p.rotation, p.rotation))
            throw input_error(table.cell(r, "R").path(), "a pair of one type needs a symmetric rotation R (R = R^T), so that "
                                                         "the energy of two patches does not depend on their order");
        if (i != j && given[j * nt + i]) {
            const CosrapPatch::Params<double>& other = config.cosrap[j * nt + i];
            if (other.E != p.E || other.Kswt != p.Kswt || other.Krap != p.Krap || other.rc != p.rc)
                throw input_error(table.row(r).path(), "expected the E, Kswt, Krap and rc of the pair (" +
                                                           config.typeNames[j] + ", " + config.typeNames[i] + ")");
            if (!transposes(other.rotation, p.rotation))
                throw input_error(table.cell(r, "R").path(), "expected the transpose of the rotation R of the pair (" +
                                                                 config.typeNames[j] + ", " + config.typeNames[i] + ")");
            continue;
        }
        CosrapPatch::Params<double> reverse = p;
        reverse.rotation = {p.rotation.x, -p.rotation.y, -p.rotation.z, -p.rotation.w};
        config.cosrap[i * nt + j] = p;
        config.cosrap[j * nt + i] = reverse;
        config.cosrapListed[i * nt + j] = config.cosrapListed[j * nt + i] = 1;
        config.cutoff = std::max(config.cutoff, p.rc);
    }
}

void read_linker(const TrackedNode& node, PatchyConfig& config) {
    const int nt = config.ntypes();
    const double surface =
        input::read_parameters(node, {with_default(number("surfacePosition", "length"), 0.0)})["surfacePosition"];
    config.linker.assign(nt, {0.0, 1.0, surface});
    config.linkerListed.assign(nt, 0);
    const input::Table table = input::read_table(node, {"name", "epsilon", "sigma"});
    for (size_t r = 0; r < table.rows(); ++r) {
        const int t = patch_type(config, table.cell(r, "name"));
        if (config.linkerListed[t]) throw input_error(table.row(r).path(), "type listed twice");
        config.linker[t] = {read_number(table.cell(r, "epsilon"), number("epsilon", "energy")),
                            read_number(table.cell(r, "sigma"), number("sigma", "length^2", Must::be_positive)), surface};
        config.linkerListed[t] = 1;
    }
}

void read_patch_forcefield(const TrackedNode& topology, const SystemDescription& system, PatchyConfig& config) {
    const TrackedNode forceField = topology.at("forceField");
    std::optional<PatchList> list;
    for (const std::string& name : forceField.keys()) {
        const TrackedNode node = forceField.at(name);
        const auto [cls, subclass] = type_of_entry(node);
        if (cls != "VerletConditionalListSet") continue;
        if (list) throw input_error(node.path(), "one neighbour list per patchy entry (its pair terms share it)");
        list = read_patch_list(node, name, subclass);
    }
    std::set<std::string> seen;
    for (const std::string& name : forceField.keys()) {
        const TrackedNode node = forceField.at(name);
        const auto [cls, subclass] = type_of_entry(node);
        if (cls == "VerletConditionalListSet") continue;
        const std::string key = "[\"" + cls + "\", \"" + subclass + "\"]";
        if (!seen.insert(key).second)
            throw input_error(node.path(), "a second " + key + " term in one patchy entry (give each term once)");
        if (cls == "NonBondedPatches" && subclass == "DistanceSwitchCosine") {
            choose_condition(node, list ? &*list : nullptr, config);
            read_cosine(node, config);
        } else if (cls == "NonBondedPatches" && subclass == "COSRAP") {
            choose_condition(node, list ? &*list : nullptr, config);
            read_cosrap(node, config);
        } else if (cls == "SurfacePatches" && subclass == "Linker") {
            read_linker(node, config);
        } else {
            throw input_error(node.path() + ".type", "unknown patch component " + key + " (expected [\"NonBondedPatches\", "
                                                     "\"DistanceSwitchCosine\"], [\"NonBondedPatches\", \"COSRAP\"] or "
                                                     "[\"SurfacePatches\", \"Linker\"])");
        }
        if (const auto params = node.find("parameters")) params->check_all_used();
    }
    if (config.hasPairs && !cutoff_fits_box(config.cutoff, system.box))
        throw input_error(forceField.path(), "the patches' cutoff " + std::to_string(config.cutoff) +
                                                 " is not shorter than half the box");
}

ForceFieldComponent configure(ForceFieldComponent c, const ComponentEntry& entry, const SystemDescription& system) {
    auto config = std::make_shared<PatchyConfig>();
    config->dynamic = c.key.subclass == "DynamicallyBondedPatchyParticles";
    for (int64_t i = 1; i < system.numParticles(); ++i)
        if (system.batchId[i] != system.batchId[0])
            throw Error(STRUCTMD_ERR_UNSUPPORTED, entry.node.path() + ": patchy particles in several batches (batchId) "
                                                                      "are not supported");
    // UAMMD-structured has patches on every particle only; so do patches here.
    const TrackedNode params = input::parameters_of(entry.node);
    if (params.valid() && params.has("group") && params.get<std::string>("group") != "All")
        throw Error(STRUCTMD_ERR_UNSUPPORTED, entry.node.path() + ".parameters.group: patchy particles act on every "
                                                                  "particle (\"All\"), not on a group");
    const TrackedNode global = entry.node.at("patchesGlobal");
    read_types(global, *config);
    read_fundamental(global, *config);
    const TrackedNode topology = entry.node.at("patchesTopology");
    read_patches(entry.node, topology, system, *config);
    read_patch_forcefield(topology, system, *config);
    c.config = config;
    return c;
}

}  // namespace

ForceFieldComponent PatchyParticlesComponent::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.configure = [c](const ComponentEntry& entry, const SystemDescription& system) { return configure(c, entry, system); };
    return c;
}

}  // namespace structmd
