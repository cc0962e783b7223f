#pragma once
// The simulation steps the engine knows, one registry entry each: the key ["Class","SubClass"], every
// parameter the step reads (the shared intervalStep, startStep, endStep and group included) with its
// kind, default, units and rule, and the factory that builds the step from the values read. The
// reader (read_simulation_steps), the docs check and structmd_get_info iterate the registry, and a
// step's factory can only read the parameters its entry declares. A new step is its class file (with
// its entry function) and one line in simulation_step_registry().
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/logger.hpp"
#include "core/parameters.hpp"
#include "core/registry.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "input/description.hpp"
#include "steps/simulation_step.hpp"

namespace structmd {

class ForceFieldComponents;  // forcefield/component_set.hpp

// What a step parameter holds in JSON.
// texts, numbers: lists; object: a JSON object the step reads itself (a plugin's named parameters)
enum class StepValue { integer, number, text, flag, texts, numbers, object };

struct StepParameter {
    const char* name;
    StepValue kind;
    nlohmann::json fallback;      // the value an absent parameter takes; null: required
    Must must = Must::be_finite;  // integers and numbers: the rule checked on reading
    const char* units = "";       // what the number measures ("steps", "length"), for docs and messages
    const char* note = "";        // rules the factory checks beyond `must`, for the docs

    bool required() const { return fallback.is_null(); }
};

// The values of a step entry's parameters, read and checked against its schema. Asking for a
// parameter the schema does not declare, or as another kind, is an internal error.
class StepParameters {
public:
    // Reads every parameter of `schema` from the "parameters" object of `entry`. An absent required
    // parameter is an input error at <entry>.parameters.<name>, as is a value of the wrong kind or
    // one that breaks its rule.
    StepParameters(const input::TrackedNode& entry, const std::vector<StepParameter>& schema);

    bool declares(const std::string& name) const { return find(name) != nullptr; }
    int64_t integer(const std::string& name) const;
    double number(const std::string& name) const;
    std::string text(const std::string& name) const;
    bool flag(const std::string& name) const;
    std::vector<std::string> texts(const std::string& name) const;
    std::vector<double> numbers(const std::string& name) const;
    nlohmann::json object(const std::string& name) const;
    // <entry>.parameters.<name>, for the factory's own messages.
    std::string path(const std::string& name) const;

private:
    struct Value {
        const StepParameter* parameter;
        nlohmann::json value;
    };
    const Value* find(const std::string& name) const;
    const nlohmann::json& value(const std::string& name, StepValue kind) const;

    std::string entryPath_;
    std::vector<Value> values_;
};

// What a factory builds its step from.
struct StepInput {
    const std::string& name;  // the entry's key
    const std::string& path;  // the entry's JSON path, "simulationStep.<name>"
    const StepParameters& parameters;
    int group;                            // the `group` parameter's index in the force field's groups; -1: "All"
    const std::vector<uint8_t>& members;  // that group's members by particle id; empty for "All"
    const input::SystemDescription& system;
    const ForceFieldSpec& forceField;     // its bonded terms (PDB CONECT records) and entry names
    // The handle's components, whose plugins' transversers a step may run; null where the reader
    // was given none (read_simulation with the reader registry alone).
    const ForceFieldComponents* components;
    const Logger& log;
    const input::TrackedNode& node;       // the entry itself, for steps that read a table (labels, data)

    int64_t interval() const { return parameters.integer("intervalStep"); }
    int64_t start() const { return parameters.integer("startStep"); }
    int64_t end() const { return parameters.integer("endStep"); }
    // For a step that measures the whole system: ERR_UNSUPPORTED at <path>.group unless it is "All".
    void require_all_particles() const;
    // The ids of the group's particles in ascending order (every particle for "All").
    std::vector<int64_t> member_ids() const;
};

// Null for an entry that leaves nothing to run (its work is done another way).
using StepFactory = std::unique_ptr<SimulationStep> (*)(const StepInput&);

struct SimulationStepEntry {
    ComponentKey key;
    std::vector<StepParameter> parameters;  // every parameter the step reads, in the order read
    StepFactory make;
    std::vector<std::string> tableLabels = {};  // the required labels of the id table it reads, if any
    bool schedulesNothing = false;  // its factory makes no step: the engine does its work otherwise
    // Runs under spatial domains (parallel/domains_over_ranks.hpp): reads only what the handle's
    // view of the whole system gives (positions, velocities, energies), never one engine's internals.
    bool underDomains = false;
    // Runs the whole input as replicas (parallel/replica_exchange.hpp) rather than as a step of one
    // engine: its factory makes nothing, and parallel/load_over_ranks.cpp reads the entry.
    bool runsReplicas = false;
};

// The parameters every step reads (intervalStep, startStep, endStep, group) followed by its own.
std::vector<StepParameter> step_parameters(std::initializer_list<StepParameter> own);

// The built-in steps. A handle that adds steps at run time copies it and passes its copy to
// read_simulation_steps.
const Registry<SimulationStepEntry>& simulation_step_registry();

}  // namespace structmd
