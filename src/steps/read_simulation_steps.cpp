#include "steps/read_simulation_steps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.hpp"
#include "steps/gyration_radius.hpp"
#include "steps/info_step.hpp"
#include "steps/mean_square_displacement.hpp"
#include "steps/stress_measure.hpp"
#include "steps/thermodynamic_measure.hpp"
#include "steps/write_step.hpp"

namespace structmd {

namespace {

struct StepContext {
    const input::SystemDescription& system;
    const std::vector<GroupSpec>& groups;
    const Logger& log;
};

// The parameters every simulation step shares.
struct CommonParameters {
    input::TrackedNode params;
    std::string path;  // of the parameters object
    int64_t interval = 0;
    int64_t start = 0;
    int64_t end = 0;
    std::string group;             // "All" unless given
    std::vector<uint8_t> members;  // by particle id; empty for "All"
};

CommonParameters read_common(const input::ComponentEntry& entry, const StepContext& context) {
    CommonParameters common;
    common.params = entry.node.at("parameters");
    common.path = common.params.path();
    common.interval = common.params.get<int64_t>("intervalStep");
    if (common.interval <= 0) throw input_error(common.path + ".intervalStep", "expected a positive integer");
    common.start = common.params.get_or<int64_t>("startStep", 0);
    common.end = common.params.get_or<int64_t>("endStep", std::numeric_limits<int64_t>::max());
    common.group = common.params.get_or<std::string>("group", "All");
    if (common.group != "All") {
        auto found = std::find_if(context.groups.begin(), context.groups.end(),
                                  [&](const GroupSpec& g) { return g.name == common.group; });
        if (found == context.groups.end())
            throw input_error(common.path + ".group", "no group named '" + common.group +
                                                          "' (define it in a [\"Groups\", \"GroupsList\"] entry)");
        common.members = found->members;
    }
    return common;
}

// For steps that describe the whole system and cannot restrict themselves to a group.
void require_all_particles(const CommonParameters& common) {
    if (common.group != "All")
        throw Error(STRUCTMD_ERR_UNSUPPORTED, common.path + ".group: this step measures the whole system; a group "
                                                            "other than \"All\" is not supported");
}

std::unique_ptr<SimulationStep> read_thermodynamic_measure(const input::ComponentEntry& entry,
                                                           const StepContext& context) {
    const CommonParameters common = read_common(entry, context);
    require_all_particles(common);
    return std::make_unique<ThermodynamicMeasure>(entry.name, common.interval, common.start, common.end,
                                                  common.params.get<std::string>("outputFilePath"));
}

// The log line is about the whole run, so a group, which must exist, changes nothing.
std::unique_ptr<SimulationStep> read_info_step(const input::ComponentEntry& entry, const StepContext& context) {
    const CommonParameters common = read_common(entry, context);
    return std::make_unique<InfoStep>(entry.name, common.interval, common.start, common.end, context.log,
                                      context.system.currentStep);
}

std::unique_ptr<SimulationStep> read_mean_square_displacement(const input::ComponentEntry& entry,
                                                              const StepContext& context) {
    CommonParameters common = read_common(entry, context);
    return std::make_unique<MeanSquareDisplacement>(entry.name, common.interval, common.start, common.end,
                                                    common.params.get<std::string>("outputFilePath"),
                                                    std::move(common.members));
}

std::unique_ptr<SimulationStep> read_gyration_radius(const input::ComponentEntry& entry, const StepContext& context) {
    CommonParameters common = read_common(entry, context);
    return std::make_unique<GyrationRadius>(entry.name, common.interval, common.start, common.end,
                                            common.params.get<std::string>("outputFilePath"),
                                            std::move(common.members));
}

std::unique_ptr<SimulationStep> read_stress_measure(const input::ComponentEntry& entry, const StepContext& context) {
    CommonParameters common = read_common(entry, context);
    const std::string output = common.params.get<std::string>("outputFilePath");
    const double radius = common.params.get<double>("radiusCutOff");
    const std::string radiusPath = common.path + ".radiusCutOff";
    if (!(radius > 0.0) || !std::isfinite(radius)) throw input_error(radiusPath, "expected a positive length");
    const auto& box = context.system.box;
    const double halfBox = 0.5 * std::min({box[0], box[1], box[2]});
    if (radius >= halfBox) {
        std::ostringstream what;
        what << "radiusCutOff " << radius << " is not shorter than half the box (" << halfBox << ")";
        throw input_error(radiusPath, what.str());
    }
    return std::make_unique<StressMeasure>(entry.name, common.interval, common.start, common.end, output, radius,
                                           std::move(common.members));
}

std::unique_ptr<SimulationStep> read_write_step(const input::ComponentEntry& entry, const StepContext& context) {
    CommonParameters common = read_common(entry, context);
    return make_write_step(entry.name, common.params, common.interval, common.start, common.end,
                           std::move(common.members), context.system);
}

using StepReader = std::unique_ptr<SimulationStep> (*)(const input::ComponentEntry&, const StepContext&);

struct RegisteredStep {
    const char* cls;
    const char* subclass;
    StepReader read;
};

// Every simulation step the engine knows, one line each.
const RegisteredStep kRegistry[] = {
    {"ThermodynamicMeasure", "ThermodynamicQuantityMeasure", read_thermodynamic_measure},
    {"UtilsStep", "InfoStep", read_info_step},
    {"GeometricalMeasure", "MeanSquareDisplacement", read_mean_square_displacement},
    {"GeometricalMeasure", "GyrationRadius", read_gyration_radius},
    {"MechanicalMeasure", "StressMeasure", read_stress_measure},
    {"WriteStep", "WriteStep", read_write_step},
};

}  // namespace

std::vector<std::unique_ptr<SimulationStep>> read_simulation_steps(const input::SystemDescription& system,
                                                                   const std::vector<GroupSpec>& groups,
                                                                   const Logger& log) {
    const StepContext context{system, groups, log};
    std::vector<std::unique_ptr<SimulationStep>> steps;
    for (const input::ComponentEntry& entry : system.simulationSteps) {
        const auto registered = std::find_if(std::begin(kRegistry), std::end(kRegistry), [&](const RegisteredStep& r) {
            return entry.cls == r.cls && entry.subclass == r.subclass;
        });
        if (registered == std::end(kRegistry)) {
            std::string known;
            for (const RegisteredStep& r : kRegistry)
                known += std::string(known.empty() ? "" : ", ") + "[\"" + r.cls + "\", \"" + r.subclass + "\"]";
            throw input_error(entry.node.path() + ".type", "unknown simulation step [\"" + entry.cls + "\", \"" +
                                                               entry.subclass + "\"]; known: " + known);
        }
        steps.push_back(registered->read(entry, context));
    }
    return steps;
}

}  // namespace structmd
