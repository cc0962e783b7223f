// parse_document: JSON text -> SystemDescription, validating the sections every simulation shares
// (system, global, state, topology.structure, the integrator schedule). Components are left in
// ComponentEntry nodes for their own readers.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "core/box.hpp"
#include "core/error.hpp"
#include "input/description.hpp"
#include "input/document_builder.hpp"

namespace structmd::input {
namespace {

using nlohmann::json;

// Bounds that keep every derived count finite: the step counter after a whole schedule. The box's
// bound, kLargestBoxLength, is in core/box.hpp; the nesting's, in document_builder.cpp.
constexpr int64_t kLargestStepCount = 1000000000000000;

std::string join(const std::vector<std::string>& words) {
    std::string text;
    for (const std::string& word : words) text += (text.empty() ? "" : ", ") + word;
    return text;
}

struct ComponentType {
    std::string cls;
    std::string subclass;
};

ComponentType read_type(const TrackedNode& entry) {
    const TrackedNode type = entry.at("type");
    const json& value = type.json();
    if (!value.is_array() || value.size() != 2 || !value[0].is_string() || !value[1].is_string())
        throw input_error(type.path(), "expected [Class, SubClass] (two strings), got " + value.dump());
    return {value[0].get<std::string>(), value[1].get<std::string>()};
}

Error unknown_component(const TrackedNode& entry, const ComponentType& type) {
    return input_error(entry.path() + ".type", "unknown component [" + type.cls + ", " + type.subclass + "]");
}

std::vector<ComponentEntry> read_components(const TrackedNode& section) {
    std::vector<ComponentEntry> entries;
    for (const std::string& name : section.keys()) {
        TrackedNode entry = section.at(name);
        ComponentType type = read_type(entry);
        entries.push_back({name, std::move(type.cls), std::move(type.subclass), std::move(entry)});
    }
    return entries;
}

// Finds the entry of each class in a section whose entries are told apart by type, not by key name.
class EntriesByClass {
public:
    explicit EntriesByClass(const TrackedNode& section) : section_(section) {
        for (ComponentEntry& entry : read_components(section)) {
            auto [existing, inserted] = byClass_.emplace(entry.cls, entry);
            if (!inserted)
                throw input_error(entry.node.path(), "a second " + entry.cls + " entry in " + section.path() +
                                                         " (the first is " + existing->second.node.path() + ")");
        }
    }
    const ComponentEntry* find(const std::string& cls) const {
        auto entry = byClass_.find(cls);
        return entry == byClass_.end() ? nullptr : &entry->second;
    }
    const ComponentEntry& at(const std::string& cls, const std::string& subclass) const {
        const ComponentEntry* entry = find(cls);
        if (!entry)
            throw input_error(section_.path(), "missing the [" + cls + ", " + subclass + "] entry");
        return *entry;
    }
    std::vector<const ComponentEntry*> all() const {
        std::vector<const ComponentEntry*> entries;
        for (const auto& item : byClass_) entries.push_back(&item.second);
        return entries;
    }

private:
    TrackedNode section_;
    std::map<std::string, ComponentEntry> byClass_;
};

void require_subclass(const ComponentEntry& entry, const std::string& subclass) {
    if (entry.subclass != subclass) throw unknown_component(entry.node, {entry.cls, entry.subclass});
}

double read_at_least(const TrackedNode& node, double lowest, const std::string& quantity) {
    const double value = node.as<double>();
    if (value < lowest)
        throw input_error(node.path(), quantity + " must be >= " + json(lowest).dump() + ", got " + node.json().dump());
    return value;
}

void read_system(const TrackedNode& system, SystemDescription& description) {
    std::optional<ComponentEntry> information;
    std::optional<std::string> backupPath;
    for (ComponentEntry& entry : read_components(system)) {
        if (entry.cls == "Simulation" && entry.subclass == "Backup") {
            if (backupPath)
                throw input_error(entry.node.path(), "a second [Simulation, Backup] entry (the first is " +
                                                         *backupPath + ")");
            backupPath = entry.node.path();
            const TrackedNode parameters = entry.node.at("parameters");
            BackupSettings backup;
            backup.filePath = parameters.get<std::string>("backupFilePath");
            backup.intervalStep = parameters.get<int64_t>("backupIntervalStep");
            if (backup.intervalStep <= 0)
                throw input_error(parameters.path() + ".backupIntervalStep", "expected a positive integer");
            backup.startStep = parameters.get_or<int64_t>("backupStartStep", 0);
            backup.endStep = parameters.get_or<int64_t>("backupEndStep", INT64_MAX);
            // What UAMMD-structured writes into the documents it restarts from: checked, not kept, as
            // the restart's step comes from global.fundamental's currentStep.
            parameters.get_or<bool>("restartedFromBackup", false);
            if (parameters.get_or<int64_t>("lastBackupStep", 0) < 0)
                throw input_error(parameters.path() + ".lastBackupStep", "expected a step >= 0");
            description.backup = backup;
            continue;
        }
        if (entry.cls != "Simulation" || entry.subclass != "Information")
            throw unknown_component(entry.node, {entry.cls, entry.subclass});
        if (information)
            throw input_error(entry.node.path(), "a second [Simulation, Information] entry (the first is " +
                                                     information->node.path() + ")");
        information = std::move(entry);
    }
    if (!information) throw input_error(system.path(), "missing the [Simulation, Information] entry");
    const TrackedNode parameters = information->node.at("parameters");
    description.name = parameters.get<std::string>("name");
    description.seed = parameters.get_or<uint64_t>("seed", kDefaultSeed);
}

void read_units(const ComponentEntry& entry, Units& units) {
    units.name = entry.subclass;
    if (entry.subclass == "None") {
        units.boltzmann = 1.0;
        units.electricConversion = 1.0;
    } else if (entry.subclass == "KcalMol_A") {
        units.boltzmann = 1.987191e-3;         // kcal/(mol K)
        units.electricConversion = 332.0716;  // kcal A/(mol e^2)
    } else if (entry.subclass == "lenSI") {
        // SI with lengths in lengthScale metres (UAMMD-structured's lenSI): masses in lengthScale^3
        // g and times in lengthScale s, so energies scale as lengthScale^3 J and charges as
        // lengthScale C, and temperatures are in K.
        double scale = 1.0;
        if (const auto parameters = entry.node.find("parameters"))
            if (const auto lengthScale = parameters->find("lengthScale")) {
                scale = lengthScale->as<double>();
                if (!(scale > 0.0 && std::isfinite(scale)))
                    throw input_error(lengthScale->path(), "lengthScale must be a positive length in metres, got " +
                                                              lengthScale->json().dump());
            }
        units.boltzmann = 1.380649e-23 / (scale * scale * scale);  // J/K over lengthScale^3
        units.electricConversion = 8.987551e9 * scale * scale;     // N m^2 C^-2 over lengthScale^-2
    } else {
        throw unknown_component(entry.node, {entry.cls, entry.subclass});
    }
}

// ["Types","Basic"], or ["Types","Polarizable"]: the same with each type's polarizability, which
// particles of the type take unless the state gives their own (apply_type_polarizabilities).
void read_types(const ComponentEntry& entry, std::vector<ParticleType>& types) {
    if (entry.subclass != "Basic" && entry.subclass != "Polarizable")
        throw unknown_component(entry.node, {entry.cls, entry.subclass});
    const bool polarizable = entry.subclass == "Polarizable";
    std::vector<std::string> labels{"name", "mass", "radius", "charge"};
    if (polarizable) labels.push_back("polarizability");
    const Table table = read_table(entry.node, labels);
    for (size_t row = 0; row < table.rows(); ++row) {
        const TrackedNode nameCell = table.cell(row, "name");
        ParticleType type;
        type.name = nameCell.as<std::string>();
        for (size_t earlier = 0; earlier < types.size(); ++earlier)
            if (types[earlier].name == type.name)
                throw input_error(nameCell.path(), "type '" + type.name + "' appears twice (first at " +
                                                       table.cell(earlier, "name").path() + ")");
        type.mass = read_at_least(table.cell(row, "mass"), 0.0, "mass");
        type.radius = read_at_least(table.cell(row, "radius"), 0.0, "radius");
        type.charge = table.cell(row, "charge").as<double>();
        if (polarizable) type.polarizability = table.cell(row, "polarizability").as<double>();
        types.push_back(std::move(type));
    }
}

// One box length: a number > 0 and <= 1e15 (a periodic axis), or 0 or "inf" (an open axis, kept as
// infinity): UAMMD's Box takes a length of 0 or infinity as a non-periodic axis, and JSON has no
// infinity, so the string stands for it.
double read_box_length(const TrackedNode& cell) {
    if (cell.is_string()) {
        const std::string text = cell.as<std::string>();
        if (text == "inf" || text == "infinity" || text == "Infinity") return kOpenAxis;
    } else if (cell.is_number()) {
        const double length = cell.as<double>();
        if (length == 0.0) return kOpenAxis;
        if (length > 0.0 && length <= kLargestBoxLength) return length;
    }
    throw input_error(cell.path(), "box length must be > 0 and <= 1e15, or 0 or \"inf\" for an open "
                                   "(non-periodic) axis: expected such a number or \"inf\", got " +
                                       cell.json().dump());
}

// ["Ensemble","NVT"], or ["Ensemble","NVTlambda"]: the same with the coupling parameter lambda of
// the terms that depend on it (lambda_coupling.hpp), which simulation steps may change during a run.
void read_ensemble(const ComponentEntry& entry, SystemDescription& description) {
    if (entry.subclass != "NVT" && entry.subclass != "NVTlambda")
        throw unknown_component(entry.node, {entry.cls, entry.subclass});
    const bool withLambda = entry.subclass == "NVTlambda";
    const Table table = read_table(entry.node, withLambda ? std::vector<std::string>{"box", "temperature", "lambda"}
                                                          : std::vector<std::string>{"box", "temperature"});
    if (table.rows() != 1)
        throw input_error(entry.node.path() + ".data", "expected exactly one row, got " + std::to_string(table.rows()));
    const TrackedNode boxCell = table.cell(0, "box");
    if (!boxCell.is_array() || boxCell.size() != 3)
        throw input_error(boxCell.path(), "expected [x, y, z] (the box lengths), got " + boxCell.json().dump());
    for (size_t axis = 0; axis < 3; ++axis) description.box[axis] = read_box_length(boxCell.at(axis));
    description.boxPath = boxCell.path();
    description.temperature = read_at_least(table.cell(0, "temperature"), 0.0, "temperature");
    if (withLambda) {
        const TrackedNode lambdaCell = table.cell(0, "lambda");
        const double lambda = lambdaCell.as<double>();
        if (!(lambda >= 0.0 && lambda <= 1.0))
            throw input_error(lambdaCell.path(), "lambda must be in [0, 1], got " + lambdaCell.json().dump());
        description.lambda = lambda;
    }
}

void read_fundamental(const ComponentEntry& entry, SystemDescription& description) {
    require_subclass(entry, "Time");
    const auto parameters = entry.node.find("parameters");
    if (!parameters) return;
    if (const auto step = parameters->find("currentStep")) {
        description.currentStep = step->as<int64_t>();
        if (description.currentStep < 0 || description.currentStep > kLargestStepCount)
            throw input_error(step->path(), "currentStep must be >= 0 and <= 1e15, got " + step->json().dump());
    }
    description.simulationTime = parameters->get_or<double>("simulationTime", 0.0);
    if (const auto timeStep = parameters->find("timeStep")) {
        description.timeStep = timeStep->as<double>();
        if (!(*description.timeStep > 0.0))
            throw input_error(timeStep->path(), "timeStep must be > 0, got " + timeStep->json().dump());
    }
}

void read_global(const TrackedNode& global, SystemDescription& description) {
    const EntriesByClass entries(global);
    for (const ComponentEntry* entry : entries.all()) {
        const std::string& cls = entry->cls;
        if (cls != "Units" && cls != "Types" && cls != "Ensemble" && cls != "Fundamental")
            throw unknown_component(entry->node, {entry->cls, entry->subclass});
    }
    if (const ComponentEntry* units = entries.find("Units")) read_units(*units, description.units);
    const ComponentEntry& types = entries.at("Types", "Basic");
    read_types(types, description.types);
    description.typesArePolarizable = types.subclass == "Polarizable";
    read_ensemble(entries.at("Ensemble", "NVT"), description);
    if (const ComponentEntry* fundamental = entries.find("Fundamental")) read_fundamental(*fundamental, description);
}

// Reads a table whose rows are particles; returns the particle id of each row, checking that the
// ids are integers in 0..N-1, each given once.
std::vector<int64_t> read_row_ids(const Table& table, int64_t particleCount, const std::string& idRange) {
    std::vector<int64_t> idOfRow(table.rows());
    std::vector<int64_t> rowOfId(static_cast<size_t>(particleCount), -1);
    for (size_t row = 0; row < table.rows(); ++row) {
        const TrackedNode idCell = table.cell(row, "id");
        const int64_t id = idCell.as<int64_t>();
        if (id < 0 || id >= particleCount)
            throw input_error(idCell.path(), "particle id " + std::to_string(id) + " is outside " + idRange);
        int64_t& firstRow = rowOfId[static_cast<size_t>(id)];
        if (firstRow >= 0)
            throw input_error(idCell.path(), "particle id " + std::to_string(id) + " appears twice (first at " +
                                                 table.row(static_cast<size_t>(firstRow)).path() + ")");
        firstRow = static_cast<int64_t>(row);
        idOfRow[row] = id;
    }
    return idOfRow;
}

// The state table with the particle id of each row; its mass, radius and charge columns wait until
// the structure has given each particle its type.
struct StateTable {
    Table table;
    std::vector<int64_t> idOfRow;
};

// An orientation [q0, q1, q2, q3] (scalar first, as UAMMD-structured writes it): four numbers
// of unit norm, to the few digits a generator may print; returned normalised to full precision.
std::array<double, 4> read_quaternion(const TrackedNode& cell) {
    if (!cell.is_array() || cell.size() != 4) throw input_error(cell.path(), "expected a quaternion [q0, q1, q2, q3]");
    std::array<double, 4> q{};
    double norm2 = 0.0;
    for (size_t k = 0; k < 4; ++k) {
        q[k] = cell.at(k).as<double>();
        norm2 += q[k] * q[k];
    }
    if (!(std::abs(norm2 - 1.0) < 1e-4))
        throw input_error(cell.path(), "a direction quaternion must have unit norm, got norm^2 = " + std::to_string(norm2));
    for (double& component : q) component /= std::sqrt(norm2);
    return q;
}

// A magnetic moment as UAMMD-structured writes it, [mx, my, mz, M]: a direction in the particle's body
// frame and the moment's magnitude M >= 0; the direction is returned normalised (any direction of a
// moment of magnitude 0 reads as the body's z axis).
std::array<double, 4> read_magnetization(const TrackedNode& cell) {
    if (!cell.is_array() || cell.size() != 4)
        throw input_error(cell.path(), "expected a magnetization [mx, my, mz, M] (body-frame direction, magnitude)");
    std::array<double, 4> m{};
    for (size_t k = 0; k < 4; ++k) m[k] = cell.at(k).as<double>();
    if (!(m[3] >= 0.0)) throw input_error(cell.path() + "[3]", "the moment's magnitude must be >= 0");
    const double norm = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    if (m[3] == 0.0 && !(norm > 0.0)) return {0.0, 0.0, 1.0, 0.0};
    if (!(norm > 0.0)) throw input_error(cell.path(), "the moment's direction [mx, my, mz] must not be zero");
    for (size_t k = 0; k < 3; ++k) m[k] /= norm;
    return m;
}

// A state column's values by particle id, each checked against what the column's values must be.
std::vector<double> read_state_column(const Table& table, const std::vector<int64_t>& idOfRow, StateColumn column) {
    const StateColumnTraits& c = traits(column);
    std::vector<double> values(table.rows());
    for (size_t row = 0; row < table.rows(); ++row) {
        const TrackedNode cell = table.cell(row, c.label);
        double& value = values[static_cast<size_t>(idOfRow[row])];
        value = c.values == ColumnValues::atLeastZero ? read_at_least(cell, 0.0, c.label) : cell.as<double>();
        if (c.values == ColumnValues::positive && !(value > 0.0))
            throw input_error(cell.path(), std::string(c.label) + " must be > 0");
    }
    return values;
}

StateTable read_state(const TrackedNode& state, SystemDescription& description) {
    std::vector<std::string> optional{"velocity", "mass", "radius", "charge", "direction", "magnetization"};
    for_each_state_column([&](StateColumn c) { optional.push_back(traits(c).label); });
    // UAMMD-structured reads a state row's cells by its labels and ignores any past them; two of its
    // own generators (Magnetism-Dipolar*) write such rows.
    Table table = read_table(state, {"id", "position"}, optional, TrailingCells::ignored);
    const size_t labelCount = state.at("labels").size();
    if (const TrailingCellRows trailing = rows_with_trailing_cells(state, labelCount); trailing.count > 0)
        description.warnings.push_back(trailing.firstPath + ": row has " + std::to_string(trailing.firstCells) +
                                       " cells, labels has " + std::to_string(labelCount) + " (" +
                                       std::to_string(trailing.count) +
                                       " rows like it): the cells past the labels are ignored, as UAMMD-structured does");
    const size_t count = table.rows();
    const auto particleCount = static_cast<int64_t>(count);
    std::vector<int64_t> idOfRow =
        read_row_ids(table, particleCount,
                     "0.." + std::to_string(particleCount - 1) + " (ids must cover 0..N-1, N = " +
                         std::to_string(particleCount) + " rows)");
    // JSON cannot hold an infinite or NaN number (the parser rejects overflowing literals), so every
    // coordinate read here is finite.
    description.positions.resize(count);
    if (table.has("velocity")) description.velocities.resize(count);
    if (table.has("direction")) description.orientations.resize(count);
    if (table.has("magnetization")) description.magnetizations.resize(count);
    for (size_t row = 0; row < count; ++row) {
        const auto id = static_cast<size_t>(idOfRow[row]);
        description.positions[id] = table.cell(row, "position").as<Vec3d>();
        if (table.has("velocity")) description.velocities[id] = table.cell(row, "velocity").as<Vec3d>();
        if (table.has("direction")) description.orientations[id] = read_quaternion(table.cell(row, "direction"));
        if (table.has("magnetization"))
            description.magnetizations[id] = read_magnetization(table.cell(row, "magnetization"));
    }
    for_each_state_column([&](StateColumn c) {
        if (table.has(traits(c).label)) description.stateColumns[c] = read_state_column(table, idOfRow, c);
    });
    return {std::move(table), std::move(idOfRow)};
}

// Applies the state's per-particle mass, radius and charge over the values of each particle's type.
void apply_state_overrides(const StateTable& state, SystemDescription& description) {
    const Table& table = state.table;
    for (size_t row = 0; row < table.rows(); ++row) {
        const auto id = static_cast<size_t>(state.idOfRow[row]);
        if (table.has("mass")) description.mass[id] = read_at_least(table.cell(row, "mass"), 0.0, "mass");
        if (table.has("radius")) description.radius[id] = read_at_least(table.cell(row, "radius"), 0.0, "radius");
        if (table.has("charge")) description.charge[id] = table.cell(row, "charge").as<double>();
    }
}

// ["Types","Polarizable"]: each particle's polarizability from its type, unless the state has the
// column (then the state's, as UAMMD-structured does, with a warning).
void apply_type_polarizabilities(const TrackedNode& state, SystemDescription& description) {
    if (!description.typesArePolarizable) return;
    std::vector<double>& column = description.stateColumns[StateColumn::polarizability];
    if (!column.empty()) {
        description.warnings.push_back(state.path() + ": the state's polarizability column overrides the types' "
                                                      "([\"Types\",\"Polarizable\"])");
        return;
    }
    for (int32_t type : description.typeIndex)
        column.push_back(description.types[static_cast<size_t>(type)].polarizability);
}

std::string type_names(const std::vector<ParticleType>& types) {
    std::vector<std::string> names;
    for (const ParticleType& type : types) names.push_back(type.name);
    return names.empty() ? "none" : join(names);
}

void read_structure(const TrackedNode& structure, SystemDescription& description) {
    const Table table = read_table(structure, {"id", "type"}, {"resId", "chainId", "modelId", "batchId"});
    const int64_t count = description.numParticles();
    const std::vector<int64_t> idOfRow =
        read_row_ids(table, count, "the state's ids 0.." + std::to_string(count - 1));
    const auto n = static_cast<size_t>(count);
    if (table.rows() < n) {
        std::vector<bool> seen(n, false);
        for (int64_t id : idOfRow) seen[static_cast<size_t>(id)] = true;
        const auto missing = static_cast<size_t>(std::find(seen.begin(), seen.end(), false) - seen.begin());
        throw input_error(structure.path() + ".data",
                          "particle id " + std::to_string(missing) + " has no row (every state id needs exactly one)");
    }
    description.typeIndex.assign(n, 0);
    description.mass.assign(n, 0.0);
    description.radius.assign(n, 0.0);
    description.charge.assign(n, 0.0);
    description.modelId.assign(n, 0);
    description.batchId.assign(n, 0);
    if (table.has("resId")) description.resId.assign(n, 0);
    if (table.has("chainId")) description.chainId.assign(n, 0);
    const std::pair<const char*, std::vector<int32_t>*> groupings[] = {{"resId", &description.resId},
                                                                       {"chainId", &description.chainId},
                                                                       {"modelId", &description.modelId},
                                                                       {"batchId", &description.batchId}};
    for (size_t row = 0; row < table.rows(); ++row) {
        const auto id = static_cast<size_t>(idOfRow[row]);
        const TrackedNode typeCell = table.cell(row, "type");
        const std::string typeName = typeCell.as<std::string>();
        const int32_t type = description.typeId(typeName);
        if (type < 0)
            throw input_error(typeCell.path(),
                              "unknown type '" + typeName + "' (types are " + type_names(description.types) + ")");
        description.typeIndex[id] = type;
        description.mass[id] = description.types[static_cast<size_t>(type)].mass;
        description.radius[id] = description.types[static_cast<size_t>(type)].radius;
        description.charge[id] = description.types[static_cast<size_t>(type)].charge;
        for (const auto& [label, values] : groupings) {
            if (!table.has(label)) continue;
            (*values)[id] = table.cell(row, label).as<int32_t>();
        }
    }
}

// The [Schedule, Integrator] table: which integrator runs, in which order, for how many steps.
void read_schedule(const ComponentEntry& entry, SystemDescription& description) {
    require_subclass(entry, "Integrator");
    description.schedulePath = entry.node.path();
    const Table table = read_table(entry.node, {"order", "integrator", "steps"});
    const size_t count = table.rows();
    std::vector<std::string> integratorNames;
    for (const ComponentEntry& integrator : description.integrators) integratorNames.push_back(integrator.name);

    std::vector<int64_t> rowOfOrder(count + 1, -1);
    std::vector<bool> scheduled(description.integrators.size(), false);
    for (size_t row = 0; row < count; ++row) {
        ScheduleRow scheduleRow;
        const TrackedNode orderCell = table.cell(row, "order");
        const int64_t order = orderCell.as<int64_t>();
        if (order < 1 || order > static_cast<int64_t>(count))
            throw input_error(orderCell.path(), "order " + std::to_string(order) + " is outside 1.." +
                                                    std::to_string(count) + " (orders run 1, 2, 3, ... without gaps)");
        int64_t& firstRow = rowOfOrder[static_cast<size_t>(order)];
        if (firstRow >= 0)
            throw input_error(orderCell.path(), "order " + std::to_string(order) + " appears twice (first at " +
                                                    table.row(static_cast<size_t>(firstRow)).path() + ")");
        firstRow = static_cast<int64_t>(row);
        scheduleRow.order = static_cast<int>(order);

        const TrackedNode nameCell = table.cell(row, "integrator");
        scheduleRow.integrator = nameCell.as<std::string>();
        const auto named = std::find(integratorNames.begin(), integratorNames.end(), scheduleRow.integrator);
        if (named == integratorNames.end())
            throw input_error(nameCell.path(), "unknown integrator '" + scheduleRow.integrator + "' (integrators are " +
                                                   (integratorNames.empty() ? "none" : join(integratorNames)) + ")");
        scheduled[static_cast<size_t>(named - integratorNames.begin())] = true;

        const TrackedNode stepsCell = table.cell(row, "steps");
        scheduleRow.steps = stepsCell.as<int64_t>();
        if (scheduleRow.steps < 0 || scheduleRow.steps > kLargestStepCount)
            throw input_error(stepsCell.path(),
                              "steps must be >= 0 and <= 1e15, got " + std::to_string(scheduleRow.steps));
        description.schedule.push_back(std::move(scheduleRow));
    }
    for (size_t i = 0; i < scheduled.size(); ++i)
        if (!scheduled[i])
            throw input_error(description.integrators[i].node.path(),
                              "integrator not in the schedule " + description.schedulePath);
    std::sort(description.schedule.begin(), description.schedule.end(),
              [](const ScheduleRow& a, const ScheduleRow& b) { return a.order < b.order; });
}

void read_integrators(const TrackedNode& section, SystemDescription& description) {
    std::optional<ComponentEntry> schedule;
    for (ComponentEntry& entry : read_components(section)) {
        if (entry.cls == "Groups") {
            description.sectionGroups.push_back(std::move(entry));
        } else if (entry.cls != "Schedule") {
            description.integrators.push_back(std::move(entry));
        } else if (schedule) {
            throw input_error(entry.node.path(),
                              "a second schedule (the first is " + schedule->node.path() + "); exactly one is allowed");
        } else {
            schedule = std::move(entry);
        }
    }
    if (!schedule) throw input_error(section.path(), "missing the [Schedule, Integrator] entry");
    read_schedule(*schedule, description);
    schedule->node.check_all_used();
}

}  // namespace

ParsedDocument parse_document(const std::string& text) {
    ParsedDocument parsed;
    parsed.tracking = std::make_shared<TrackingState>();
    build_document(text, *parsed.tracking);
    parsed.root = TrackedNode(parsed.tracking, &parsed.tracking->document, "");
    const TrackedNode& root = parsed.root;
    if (!root.is_object())
        throw input_error("", "expected an object with the sections system, global, state, topology, ...");

    SystemDescription& description = parsed.system;
    const TrackedNode system = root.at("system");
    read_system(system, description);
    const TrackedNode global = root.at("global");
    read_global(global, description);
    const TrackedNode state = root.at("state");
    const StateTable stateTable = read_state(state, description);
    const TrackedNode topology = root.at("topology");
    const TrackedNode structure = topology.at("structure");
    read_structure(structure, description);
    apply_state_overrides(stateTable, description);
    apply_type_polarizabilities(state, description);
    if (const auto forceField = topology.find("forceField")) description.forceField = read_components(*forceField);
    if (const auto integrator = root.find("integrator")) read_integrators(*integrator, description);
    if (const auto steps = root.find("simulationStep"))
        for (ComponentEntry& entry : read_components(*steps))
            (entry.cls == "Groups" ? description.sectionGroups : description.simulationSteps).push_back(std::move(entry));

    // The sections read whole here are checked now; components and the rest are checked by the
    // caller's root.check_all_used() once every component has read its entry.
    system.check_all_used();
    global.check_all_used();
    state.check_all_used();
    structure.check_all_used();
    return parsed;
}

}  // namespace structmd::input
