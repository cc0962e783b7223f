#pragma once
// Plain, validated description of a simulation read from a UAMMD-structured document. No GPU, no
// physics: the simulation layer turns this into an engine. Particles are indexed by id (0..N-1).
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/state_columns.hpp"
#include "input/tracked_node.hpp"

namespace structmd::input {

using Vec3d = std::array<double, 3>;

struct Units {
    std::string name = "None";
    double boltzmann = 1.0;           // k_B in the units' energy per kelvin (1 for None)
    double electricConversion = 1.0;  // f in f q_i q_j / r
};

struct ParticleType {
    std::string name;
    double mass = 1.0;
    double radius = 0.5;
    double charge = 0.0;
    double polarizability = 0.0;  // ["Types","Polarizable"] only
};

// One forceField, integrator or simulationStep entry, parsed later by the component's own reader.
// The node is the entry object itself; reading a key through it marks the key as used.
struct ComponentEntry {
    std::string name;      // the entry's key, unique within its section
    std::string cls;       // type[0]
    std::string subclass;  // type[1]
    TrackedNode node;      // the entry ("type" already consumed)
};

// ["Simulation","Backup"]: a checkpoint every intervalStep steps for start <= step <= end.
struct BackupSettings {
    std::string filePath;
    int64_t intervalStep = 0;
    int64_t startStep = 0;
    int64_t endStep = INT64_MAX;
};

struct ScheduleRow {
    int order = 0;
    std::string integrator;  // an entry name of the integrator section
    int64_t steps = 0;
};

// Without a seed in system, runs stay reproducible: this fixed value (not the clock, as the
// reference does) seeds every random stream.
constexpr uint64_t kDefaultSeed = 0x5EED;

struct SystemDescription {
    // What the reader accepted but a user should hear of, each naming its path: logged as warnings
    // when the simulation is read.
    std::vector<std::string> warnings;

    // system
    std::string name;
    uint64_t seed = 0;
    std::optional<BackupSettings> backup;  // ["Simulation","Backup"]

    // global
    Units units;
    std::vector<ParticleType> types;
    bool typesArePolarizable = false;  // ["Types","Polarizable"]: particles take their type's polarizability
    Vec3d box{0, 0, 0};  // infinity along an open (non-periodic) axis
    std::string boxPath;  // the ensemble's box cell, for messages about the box
    double temperature = 0.0;  // in kelvin-like units: k_B T = units.boltzmann * temperature
    // The coupling parameter of ["Ensemble","NVTlambda"]; empty under NVT, where the terms of lambda
    // act in full (lambda = 1).
    std::optional<double> lambda;
    int64_t currentStep = 0;
    double simulationTime = 0.0;
    std::optional<double> timeStep;

    // state + topology.structure, by particle id
    std::vector<Vec3d> positions;
    std::vector<Vec3d> velocities;  // empty when the state gives none
    std::vector<std::array<double, 4>> orientations;  // the state's direction [q0, q1, q2, q3], normalised; empty when not given
    // The state's magnetization [mx, my, mz, M]: unit direction in the body frame and magnitude; empty when not given.
    std::vector<std::array<double, 4>> magnetizations;
    std::vector<int32_t> typeIndex;
    std::vector<double> mass, radius, charge;  // type values with the state's overrides applied
    std::vector<int32_t> modelId, batchId;
    std::vector<int32_t> resId, chainId;  // empty when the structure has no such column (PDB output reads them)
    PerStateColumn<std::vector<double>> stateColumns;  // core/state_columns.hpp; each empty when not given

    // components, in document order
    std::vector<ComponentEntry> forceField;
    std::vector<ComponentEntry> integrators;
    std::vector<ScheduleRow> schedule;  // sorted by order; "Schedule" entry itself not in integrators
    std::string schedulePath;           // JSON path of the schedule entry
    std::vector<ComponentEntry> simulationSteps;
    // ["Groups","GroupsList"] entries of the integrator and simulationStep sections (those of
    // topology.forceField stay in forceField): every section's groups share one namespace.
    std::vector<ComponentEntry> sectionGroups;

    int64_t numParticles() const { return static_cast<int64_t>(positions.size()); }
    int32_t typeId(const std::string& name) const {
        for (size_t i = 0; i < types.size(); ++i)
            if (types[i].name == name) return static_cast<int32_t>(i);
        return -1;
    }
};

// Parses a whole document (comments allowed) and validates the common sections. Components stay
// unread in their ComponentEntry; call root.check_all_used() once every component has been read.
struct ParsedDocument {
    std::shared_ptr<TrackingState> tracking;
    SystemDescription system;
    TrackedNode root;
};

// Throws structmd::Error(STRUCTMD_ERR_INPUT) with line and column for malformed JSON, or with the
// JSON path for a missing, mistyped or inconsistent entry.
ParsedDocument parse_document(const std::string& text);

}  // namespace structmd::input
