#include "steps/read_simulation_steps.hpp"

#include <cmath>
#include <filesystem>
#include <limits>

#include "core/error.hpp"
#include "input/read_parameters.hpp"
#include "steps/afm_max_force.hpp"
#include "steps/afm_measure.hpp"
#include "steps/center_of_mass.hpp"
#include "steps/distance_between_centers_of_mass.hpp"
#include "steps/escape_time.hpp"
#include "steps/force_between_sets_measure.hpp"
#include "steps/gyration_radius.hpp"
#include "steps/height_measure.hpp"
#include "steps/mean_angular_correlation.hpp"
#include "steps/hessian_measure.hpp"
#include "steps/info_step.hpp"
#include "steps/interactors_energy_measure.hpp"
#include "steps/magnetization_measure.hpp"
#include "steps/lambda_schedule.hpp"
#include "steps/mean_square_displacement.hpp"
#include "steps/pairwise_force_measure.hpp"
#include "steps/parallel_tempering.hpp"
#include "steps/patch_polymers.hpp"
#include "steps/particle_list_measure.hpp"
#include "steps/plugin_transverser_measure.hpp"
#include "steps/potential_measure.hpp"
#include "steps/sort_step.hpp"
#include "steps/stress_measure.hpp"
#include "steps/thermodynamic_integration.hpp"
#include "steps/thermodynamic_measure.hpp"
#include "steps/transverser_measure.hpp"
#include "steps/write_patchy_particles_step.hpp"
#include "steps/write_step.hpp"

namespace structmd {

const Registry<SimulationStepEntry>& simulation_step_registry() {
    static const Registry<SimulationStepEntry> registry = [] {
        Registry<SimulationStepEntry> steps;
        // Every simulation step the engine knows, one line each, in the order the docs list them.
        steps.add(thermodynamic_measure_entry());
        steps.add(info_step_entry());
        steps.add(interactors_energy_measure_entry());
        steps.add(mean_square_displacement_entry());
        steps.add(gyration_radius_entry());
        steps.add(mean_angular_correlation_entry());
        steps.add(center_of_mass_position_entry());
        steps.add(mean_radius_entry());
        steps.add(distances_measure_entry());
        steps.add(angles_measure_entry());
        steps.add(dihedrals_measure_entry());
        steps.add(contacts_measure_entry());
        steps.add(height_measure_entry());
        steps.add(potential_measure_entry());
        steps.add(transverser_measure_entry());
        steps.add(plugin_transverser_measure_entry());
        steps.add(stress_measure_entry());
        steps.add(hessian_measure_entry());
        steps.add(pairwise_force_measure_entry());
        steps.add(force_between_sets_measure_entry());
        steps.add(distance_between_centers_of_mass_entry());
        steps.add(afm_measure_entry());
        steps.add(afm_max_force_entry());
        steps.add(escape_sphere_time_entry());
        steps.add(escape_polygon_time_entry());
        steps.add(total_magnetization_entry());
        steps.add(mean_magnetization_entry());
        steps.add(patch_polymers_entry());
        steps.add(write_step_entry());
        steps.add(write_patchy_particles_step_entry());
        steps.add(sort_step_entry());
        steps.add(thermodynamic_integration_entry());
        steps.add(parallel_tempering_entry());
        steps.add(lambda_activation_entry());
        steps.add(lambda_cycle_entry());
        return steps;
    }();
    return registry;
}

std::vector<StepParameter> step_parameters(std::initializer_list<StepParameter> own) {
    std::vector<StepParameter> parameters = {
        {"intervalStep", StepValue::integer, nullptr, Must::be_positive, "steps"},
        {"startStep", StepValue::integer, int64_t{0}, Must::be_finite, "steps"},
        {"endStep", StepValue::integer, std::numeric_limits<int64_t>::max(), Must::be_finite, "steps",
         "the step fires for startStep <= step <= endStep; by default to the end of the run"},
        {"group", StepValue::text, "All", Must::be_finite, "",
         "the name of a [\"Groups\",\"GroupsList\"] group, or \"All\""},
    };
    parameters.insert(parameters.end(), own.begin(), own.end());
    return parameters;
}

namespace {

const char* kind_text(StepValue kind) {
    switch (kind) {
        case StepValue::integer: return "integer";
        case StepValue::number: return "number";
        case StepValue::text: return "text";
        case StepValue::flag: return "flag";
        case StepValue::texts: return "list of texts";
        case StepValue::numbers: return "list of numbers";
        case StepValue::object: return "object";
    }
    return "?";
}

// What a number is called in its rule's message: "expected a positive integer", "... length", ...
std::string what_of(const StepParameter& parameter) {
    if (parameter.kind == StepValue::integer) return "integer";
    return *parameter.units ? parameter.units : "number";
}

nlohmann::json read_value(const input::TrackedNode& node, const StepParameter& parameter) {
    switch (parameter.kind) {
        case StepValue::integer: {
            const int64_t value = node.as<int64_t>();
            input::check_rule(node, static_cast<double>(value), parameter.must, what_of(parameter));
            return value;
        }
        case StepValue::number: {
            const double value = node.as<double>();
            input::check_rule(node, value, parameter.must, what_of(parameter));
            return value;
        }
        case StepValue::text: return node.as<std::string>();
        case StepValue::flag: return node.as<bool>();
        case StepValue::texts: {
            if (!node.is_array()) throw input_error(node.path(), "expected a list of names");
            nlohmann::json names = nlohmann::json::array();
            for (size_t k = 0; k < node.size(); ++k) names.push_back(node.at(k).as<std::string>());
            return names;
        }
        case StepValue::numbers: {
            if (!node.is_array() || node.size() == 0) throw input_error(node.path(), "expected a non-empty list of numbers");
            nlohmann::json numbers = nlohmann::json::array();
            for (size_t k = 0; k < node.size(); ++k) {
                const double value = node.at(k).as<double>();
                input::check_rule(node.at(k), value, parameter.must, what_of(parameter));
                numbers.push_back(value);
            }
            return numbers;
        }
        case StepValue::object: {
            if (!node.is_object()) throw input_error(node.path(), "expected an object");
            node.mark_used();  // its keys are the step's to check, against what the object names
            return node.json();
        }
    }
    throw Error(STRUCTMD_ERR_INTERNAL, node.path() + ": parameter of no known kind");
}

// The folder of an output file must exist when the input is loaded, not only when the step first
// writes, which may be hours into the run. Files themselves are opened at that first write, so a
// failed load creates none.
void require_output_folder(const input::TrackedNode& node, const std::string& file) {
    const std::filesystem::path folder = std::filesystem::path(file).parent_path();
    std::error_code error;
    if (folder.empty() || std::filesystem::is_directory(folder, error)) return;
    const bool exists = std::filesystem::exists(folder, error);
    throw Error(STRUCTMD_ERR_IO, node.path() + (exists ? ": '" + folder.string() + "' is not a folder"
                                                       : ": the folder '" + folder.string() +
                                                             "' does not exist (structmd creates no folders)"));
}

// Relative output paths are the working directory's (as in LAMMPS, GROMACS and OpenMM): the log
// says where each file goes, so that loading an input from another folder writes nowhere unseen.
void log_output_file(const StepParameters& parameters, const std::string& entryPath, const Logger& log) {
    std::string file = parameters.text("outputFilePath");
    if (parameters.declares("outputFormat")) file += "." + parameters.text("outputFormat");
    std::error_code error;
    const std::filesystem::path absolute = std::filesystem::absolute(file, error);
    log.info(entryPath + " writes " + (error ? file : absolute.lexically_normal().string()));
}

}  // namespace

StepParameters::StepParameters(const input::TrackedNode& entry, const std::vector<StepParameter>& schema)
    : entryPath_(entry.path()) {
    const input::TrackedNode params = input::parameters_of(entry);
    for (const StepParameter& parameter : schema) {
        const auto node = params.valid() ? params.find(parameter.name) : std::nullopt;
        if (node) {
            values_.push_back({&parameter, read_value(*node, parameter)});
            if (std::string(parameter.name) == "outputFilePath")
                require_output_folder(*node, values_.back().value.get<std::string>());
        } else if (parameter.required())
            throw params.valid() ? params.missing(parameter.name, "missing required parameter")
                                 : input_error(path(parameter.name), "missing required parameter");
        else
            values_.push_back({&parameter, parameter.fallback});
    }
}

const StepParameters::Value* StepParameters::find(const std::string& name) const {
    for (const Value& value : values_)
        if (name == value.parameter->name) return &value;
    return nullptr;
}

const nlohmann::json& StepParameters::value(const std::string& name, StepValue kind) const {
    const Value* found = find(name);
    if (!found)
        throw Error(STRUCTMD_ERR_INTERNAL, path(name) + ": read by the step but not declared in its registry entry");
    if (found->parameter->kind != kind)
        throw Error(STRUCTMD_ERR_INTERNAL,
                    path(name) + ": declared as " + kind_text(found->parameter->kind) + ", read as " + kind_text(kind));
    return found->value;
}

int64_t StepParameters::integer(const std::string& name) const {
    return value(name, StepValue::integer).get<int64_t>();
}
double StepParameters::number(const std::string& name) const { return value(name, StepValue::number).get<double>(); }
std::string StepParameters::text(const std::string& name) const {
    return value(name, StepValue::text).get<std::string>();
}
bool StepParameters::flag(const std::string& name) const { return value(name, StepValue::flag).get<bool>(); }
std::vector<std::string> StepParameters::texts(const std::string& name) const {
    return value(name, StepValue::texts).get<std::vector<std::string>>();
}
std::vector<double> StepParameters::numbers(const std::string& name) const {
    return value(name, StepValue::numbers).get<std::vector<double>>();
}
nlohmann::json StepParameters::object(const std::string& name) const { return value(name, StepValue::object); }
std::string StepParameters::path(const std::string& name) const { return entryPath_ + ".parameters." + name; }

void StepInput::require_all_particles() const {
    if (group != -1)
        throw Error(STRUCTMD_ERR_UNSUPPORTED, parameters.path("group") +
                                                  ": this step measures the whole system; a group other than "
                                                  "\"All\" is not supported");
}

std::vector<int64_t> StepInput::member_ids() const {
    std::vector<int64_t> ids;
    for (int64_t id = 0; id < system.numParticles(); ++id)
        if (members.empty() || members[id]) ids.push_back(id);
    return ids;
}

std::vector<std::unique_ptr<SimulationStep>> read_simulation_steps(const Registry<SimulationStepEntry>& registry,
                                                                   const input::SystemDescription& system,
                                                                   const ForceFieldSpec& forceField,
                                                                   const ForceFieldComponents* components,
                                                                   const Logger& log) {
    static const std::vector<uint8_t> everyParticle;
    const std::vector<GroupSpec>& groups = forceField.groups;
    std::vector<std::unique_ptr<SimulationStep>> steps;
    for (const input::ComponentEntry& entry : system.simulationSteps) {
        const SimulationStepEntry& step =
            registry.at({entry.cls, entry.subclass}, entry.node.path() + ".type", "simulation step");
        const StepParameters parameters(entry.node, step.parameters);
        if (parameters.declares("outputFilePath")) log_output_file(parameters, entry.node.path(), log);
        const int group =
            parameters.declares("group") ? group_index(groups, parameters.text("group"), parameters.path("group")) : -1;
        const StepInput input{entry.name,
                              entry.node.path(),
                              parameters,
                              group,
                              group < 0 ? everyParticle : groups[static_cast<size_t>(group)].members,
                              system,
                              forceField,
                              components,
                              log,
                              entry.node};
        if (std::unique_ptr<SimulationStep> made = step.make(input)) steps.push_back(std::move(made));
    }
    return steps;
}

std::vector<std::unique_ptr<SimulationStep>> read_simulation_steps(const input::SystemDescription& system,
                                                                   const ForceFieldSpec& forceField,
                                                                   const ForceFieldComponents* components,
                                                                   const Logger& log) {
    return read_simulation_steps(simulation_step_registry(), system, forceField, components, log);
}

}  // namespace structmd
