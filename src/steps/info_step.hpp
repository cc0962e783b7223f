#pragma once
// ["UtilsStep","InfoStep"]: at each firing, an info-level line in the handle's log with the step, how
// far through the schedule it is, the speed since the previous firing and the time left at that speed.
#include <chrono>
#include <optional>
#include <string>

#include "core/logger.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class InfoStep : public SimulationStep {
public:
    // scheduleStart: the step the schedule starts from, where the progress is 0 %.
    InfoStep(std::string name, int64_t interval, int64_t start, int64_t end, Logger log, int64_t scheduleStart);

protected:
    void run(Simulation& sim) override;

private:
    struct Mark {
        int64_t step;
        std::chrono::steady_clock::time_point when;
    };

    Logger log_;
    int64_t scheduleStart_;
    std::optional<Mark> previous_;
};

SimulationStepEntry info_step_entry();

}  // namespace structmd
