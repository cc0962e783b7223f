#include "steps/read_simulation_steps.hpp"

#include <limits>

#include "core/error.hpp"
#include "steps/thermodynamic_measure.hpp"

namespace structmd {

std::vector<std::unique_ptr<SimulationStep>> read_simulation_steps(const input::SystemDescription& system) {
    std::vector<std::unique_ptr<SimulationStep>> steps;
    for (const input::ComponentEntry& entry : system.simulationSteps) {
        const std::string path = entry.node.path();
        if (entry.cls != "ThermodynamicMeasure" || entry.subclass != "ThermodynamicQuantityMeasure")
            throw input_error(path + ".type", "unknown simulation step [\"" + entry.cls + "\", \"" + entry.subclass +
                                                  "\"]; known: [\"ThermodynamicMeasure\", "
                                                  "\"ThermodynamicQuantityMeasure\"]");
        const input::TrackedNode params = entry.node.at("parameters");
        const int64_t interval = params.get<int64_t>("intervalStep");
        if (interval <= 0) throw input_error(path + ".parameters.intervalStep", "expected a positive integer");
        const int64_t start = params.get_or<int64_t>("startStep", 0);
        const int64_t end = params.get_or<int64_t>("endStep", std::numeric_limits<int64_t>::max());
        const std::string output = params.get<std::string>("outputFilePath");
        steps.push_back(std::make_unique<ThermodynamicMeasure>(entry.name, interval, start, end, output));
    }
    return steps;
}

}  // namespace structmd
