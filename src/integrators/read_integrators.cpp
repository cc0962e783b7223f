#include "integrators/read_integrators.hpp"

#include <cmath>
#include <map>

#include "core/error.hpp"

namespace structmd {

namespace {

// [Class, SubClass] -> kind; the minimiser is also known by the reference's two spellings.
const std::map<std::pair<std::string, std::string>, std::string>& kinds() {
    static const std::map<std::pair<std::string, std::string>, std::string> known = {
        {{"Verlet", "VelocityVerlet"}, "VelocityVerlet"},
        {{"Langevin", "BBK"}, "BBK"},
        {{"Langevin", "GJF"}, "GJF"},
        {{"Brownian", "EulerMaruyama"}, "EulerMaruyama"},
        {{"SteepestDescent", "SteepestDescent"}, "SteepestDescent"},
        {{"Minimization", "SteepestDescent"}, "SteepestDescent"},
        {{"Mininimization", "SteepestDescent"}, "SteepestDescent"},
    };
    return known;
}

double positive(const input::TrackedNode& params, const std::string& key) {
    const double value = params.get<double>(key);
    if (!(value > 0.0) || !std::isfinite(value)) throw input_error(params.path() + "." + key, "expected a positive number");
    return value;
}

}  // namespace

std::vector<IntegratorSpec> read_integrators(const input::SystemDescription& system,
                                             std::vector<ScheduleStage>& schedule) {
    std::vector<IntegratorSpec> integrators;
    for (const input::ComponentEntry& entry : system.integrators) {
        IntegratorSpec spec;
        spec.name = entry.name;
        spec.path = entry.node.path();
        auto kind = kinds().find({entry.cls, entry.subclass});
        if (kind == kinds().end()) {
            std::string known;
            for (const auto& [key, value] : kinds()) known += " [\"" + key.first + "\", \"" + key.second + "\"]";
            throw input_error(spec.path + ".type", "unknown integrator [\"" + entry.cls + "\", \"" + entry.subclass +
                                                       "\"]; known:" + known);
        }
        spec.kind = kind->second;
        const bool minimiser = spec.kind == "SteepestDescent";
        auto found = entry.node.find("parameters");
        if (!found && spec.kind != "VelocityVerlet")
            throw input_error(spec.path + ".parameters", "missing the integrator's parameters");
        const input::TrackedNode params = found ? *found : input::TrackedNode();

        std::optional<double> dt = system.timeStep;
        if (found)
            if (auto own = params.find("timeStep")) dt = own->as<double>();
        if (!dt && !minimiser)
            throw input_error(spec.path + ".parameters.timeStep", "missing time step (give it here or in global.fundamental)");
        if (dt && (!(*dt > 0.0) || !std::isfinite(*dt)))
            throw input_error(spec.path + ".parameters.timeStep", "expected a positive time step");
        spec.timeStep = dt.value_or(0.0);
        const double temperature = found ? params.get_or<double>("temperature", system.temperature) : system.temperature;
        if (!(temperature >= 0.0)) throw input_error(spec.path + ".parameters.temperature", "expected a temperature >= 0");
        spec.temperature = system.units.boltzmann * temperature;
        if (found) spec.group = params.get_or<std::string>("group", "");
        if (spec.group == "All") spec.group.clear();

        if (spec.kind == "BBK" || spec.kind == "GJF") {
            spec.frictionConstant = positive(params, "frictionConstant");
            spec.resetVelocities = params.get_or<bool>("resetVelocities", true);
            if (spec.kind == "BBK" && params.get_or<int64_t>("stopTransRotSteps", 0) != 0)
                throw Error(STRUCTMD_ERR_UNSUPPORTED,
                            spec.path + ".parameters.stopTransRotSteps: removing the centre-of-mass motion is not "
                                        "supported yet; leave it 0");
        } else if (spec.kind == "EulerMaruyama") {
            spec.viscosity = positive(params, "viscosity");
        } else if (minimiser) {
            spec.h = positive(params, "h");
            spec.maxObjectiveForce = positive(params, "maxObjectiveForce");
        }
        integrators.push_back(spec);
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
