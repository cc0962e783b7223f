#include "integrators/read_integrators.hpp"

#include <optional>
#include <set>

#include "core/error.hpp"
#include "input/read_parameters.hpp"
#include "input/time_step.hpp"
#include "integrators/integrators.hpp"

namespace structmd {

namespace {

struct ReaderEntries {
    Registry<IntegratorComponent> registry;

    template <template <class, class> class Integrator, class Inputs>
    void integrator(ComponentKey key) {
        registry.add({std::move(key), Inputs::parameters(), Inputs::minimiser, Inputs::needsRadius, &Inputs::validate,
                      Inputs::overdamped, Inputs::fallbackParameter, Inputs::fallbackColumn, Inputs::rotates,
                      Inputs::text_options(), Inputs::magnetic, Inputs::radiusParameter, Inputs::oneFluid,
                      Inputs::underDomains, Inputs::wholeSystemParameter, Inputs::wholeSystemEffect,
                      &Inputs::validate_in_box});
    }
};

// A named choice of the entry (required where it has no fallback), as the index of its value among
// the supported names.
double read_text_option(const input::TrackedNode& params, const TextOption& option, const std::string& entryPath) {
    const std::string path = entryPath + ".parameters." + option.name;
    const auto given = params.valid() ? params.find(option.name) : std::nullopt;
    if (!given && !option.fallback)
        throw input_error(path, "missing: give one of " + input::text_option_names(option));
    return static_cast<double>(input::choose_text_option(option, given ? given->as<std::string>() : option.fallback, path));
}

}  // namespace

const Registry<IntegratorComponent>& integrator_registry() {
    static const Registry<IntegratorComponent> builtin = [] {
        ReaderEntries entries;
        visit_builtin_integrators(entries);
        return std::move(entries.registry);
    }();
    return builtin;
}

std::vector<IntegratorSpec> read_integrators(const input::SystemDescription& system,
                                             const std::vector<GroupSpec>& groups,
                                             std::vector<ScheduleStage>& schedule,
                                             const Registry<IntegratorComponent>& registry) {
    std::vector<IntegratorSpec> integrators;
    for (const input::ComponentEntry& entry : system.integrators) {
        IntegratorSpec spec;
        spec.name = entry.name;
        spec.path = entry.node.path();
        const IntegratorComponent& component =
            registry.at({entry.cls, entry.subclass}, spec.path + ".type", "integrator");
        if (component.oneFluid && std::set<int32_t>(system.batchId.begin(), system.batchId.end()).size() > 1)
            throw Error(STRUCTMD_ERR_UNSUPPORTED, spec.path + ".type: hydrodynamics couples the particles of every batch "
                                                  "(batchId) through one fluid; batches are independent systems: give one batch");
        spec.key = component.key;
        spec.overdamped = component.overdamped;
        spec.rotates = component.rotates;
        const input::TrackedNode params = input::parameters_of(entry.node);

        const std::optional<double> dt = input::time_step_of(entry, system);
        if (!dt && !component.minimiser) {
            const std::string what = "missing time step (give it here or in global.fundamental)";
            throw params.valid() ? params.missing("timeStep", what) : input_error(spec.path + ".parameters.timeStep", what);
        }
        spec.timeStep = dt.value_or(0.0);
        const double temperature = params.valid() ? params.get_or<double>("temperature", system.temperature)
                                                  : system.temperature;
        if (!(temperature >= 0.0)) throw input_error(spec.path + ".parameters.temperature", "expected a temperature >= 0");
        spec.temperature = system.units.boltzmann * temperature;
        spec.group = group_index(groups, params.valid() ? params.get_or<std::string>("group", "All") : "All",
                                 spec.path + ".parameters.group");
        spec.parameters = input::read_parameters(entry.node, component.parameters);
        for (const TextOption& option : component.textOptions)
            spec.parameters.set(option.name, {read_text_option(params, option, spec.path)});
        component.validate(spec.parameters, spec.path);
        // Entries added at run time may leave it out, as they may the later fields.
        if (component.validateInBox) component.validateInBox(spec.parameters, system.box, spec.path);
        // The algorithm "none" (index 0) leaves the moments alone: particles without them may move.
        if (component.magnetic && spec.parameters["magneticIntegrationAlgorithm"] != 0.0 &&
            system.magnetizations.empty())
            throw input_error(spec.path + ".type", entry.cls + " " + entry.subclass +
                                                       " turns magnetic moments: the state needs a 'magnetization' column");

        const bool fromColumn = component.fallbackParameter && spec.parameters[component.fallbackParameter] == 0.0;
        const std::string fallbackLabel = traits(component.fallbackColumn).label;
        if (fromColumn && system.stateColumns[component.fallbackColumn].empty())
            throw input_error(spec.path + ".parameters." + component.fallbackParameter,
                              "missing: give it here, or each particle's in a state column '" + fallbackLabel + "'");
        // A rotating integrator takes its rotational mobility from the same place as its translational one.
        if (fromColumn && component.rotates && system.stateColumns[StateColumn::rotationalSelfDiffusion].empty())
            throw input_error(spec.path + ".parameters." + component.fallbackParameter,
                              "missing: give it here, or each particle's in state columns '" + fallbackLabel +
                                  "' and 'rotationalSelfDiffusion'");
        if (fromColumn && component.overdamped && !(spec.temperature > 0.0))
            throw input_error(spec.path + ".parameters.temperature",
                              "the mobility D / (k_B T) from the state's " + fallbackLabel +
                                  " needs a temperature > 0");
        const bool radiusGiven = component.radiusParameter && spec.parameters[component.radiusParameter] > 0.0;
        if (component.needsRadius && !fromColumn && !radiusGiven)
            for (int64_t i = 0; i < system.numParticles(); ++i)
                if ((spec.group < 0 || groups[spec.group].members[i]) && !(system.radius[i] > 0.0))
                    throw input_error(spec.path, "particle id " + std::to_string(i) + " has radius " +
                                                     std::to_string(system.radius[i]) + ": " + entry.cls + " " +
                                                     entry.subclass + " needs a positive radius" +
                                                     (component.radiusParameter
                                                          ? std::string(" (or parameters.") + component.radiusParameter + ")"
                                                          : std::string()));
        integrators.push_back(std::move(spec));
    }
    schedule.clear();
    for (const input::ScheduleRow& row : system.schedule) {
        ScheduleStage stage;
        for (size_t k = 0; k < integrators.size(); ++k)
            if (integrators[k].name == row.integrator) stage.integrator = static_cast<int>(k);
        stage.steps = row.steps;
        schedule.push_back(stage);
    }
    return integrators;
}

}  // namespace structmd
