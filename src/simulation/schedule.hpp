#pragma once
// The schedule: which integrator runs each step, from the first step of the input on.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "integrators/integrator_spec.hpp"

namespace structmd {

class Schedule {
public:
    Schedule(int64_t firstStep, std::vector<ScheduleStage> stages) : firstStep_(firstStep), stages_(std::move(stages)) {}

    int64_t first_step() const { return firstStep_; }
    int64_t final_step() const {
        int64_t last = firstStep_;
        for (const ScheduleStage& stage : stages_) last += stage.steps;
        return last;
    }
    int stages() const { return static_cast<int>(stages_.size()); }
    int integrator_of(int stage) const { return stages_[stage].integrator; }

    // The stage the step after `step` belongs to. Past the end of the schedule the last stage that
    // ran goes on (a coupling driver decides the run's length as it goes).
    int stage_after(int64_t step) const {
        if (stages_.empty()) throw Error(STRUCTMD_ERR_INTERNAL, "a schedule without stages");
        int64_t offset = step - firstStep_;
        int last = static_cast<int>(stages_.size()) - 1;
        for (size_t k = 0; k < stages_.size(); ++k) {
            if (offset < stages_[k].steps) return static_cast<int>(k);
            offset -= stages_[k].steps;
            if (stages_[k].steps > 0) last = static_cast<int>(k);
        }
        return last;
    }

private:
    int64_t firstStep_;
    std::vector<ScheduleStage> stages_;
};

}  // namespace structmd
