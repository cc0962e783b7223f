#include "steps/info_step.hpp"

#include <cmath>
#include <cstdio>

namespace structmd {

namespace {

// "H:MM:SS", hours unbounded.
std::string clock_text(double seconds) {
    const long long total = std::llround(seconds);
    char text[48];
    std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", total / 3600, total / 60 % 60, total % 60);
    return text;
}

}  // namespace

InfoStep::InfoStep(std::string name, int64_t interval, int64_t start, int64_t end, Logger log, int64_t scheduleStart)
    : SimulationStep(std::move(name), interval, start, end), log_(log), scheduleStart_(scheduleStart) {}

void InfoStep::run(Simulation& sim) {
    if (!log_.enabled(LogLevel::info)) return;
    const Mark now{sim.current_step(), std::chrono::steady_clock::now()};
    const int64_t last = sim.final_step();
    const double span = static_cast<double>(last - scheduleStart_);
    const double percent = span > 0 ? 100.0 * static_cast<double>(now.step - scheduleStart_) / span : 100.0;
    const bool past = now.step > last;  // structmd_step goes on with the last integrator

    char line[160];
    if (past)
        std::snprintf(line, sizeof line, "step %lld, past the schedule's end at %lld", static_cast<long long>(now.step),
                      static_cast<long long>(last));
    else
        std::snprintf(line, sizeof line, "step %lld of %lld (%.1f %%)", static_cast<long long>(now.step),
                      static_cast<long long>(last), percent);
    std::string message = "simulationStep." + name() + ": " + line;
    if (previous_ && now.step > previous_->step && !past) {
        const double seconds = std::chrono::duration<double>(now.when - previous_->when).count();
        if (seconds > 0) {
            const double rate = static_cast<double>(now.step - previous_->step) / seconds;
            std::snprintf(line, sizeof line, ", %.4g steps/s, ETA %s", rate,
                          clock_text(static_cast<double>(last - now.step) / rate).c_str());
            message += line;
        }
    }
    log_.info(message);
    previous_ = now;
}

namespace {

// The log line is about the whole run, so a group, which must exist, changes nothing.
std::unique_ptr<SimulationStep> make(const StepInput& in) {
    return std::make_unique<InfoStep>(in.name, in.interval(), in.start(), in.end(), in.log, in.system.currentStep);
}

}  // namespace

SimulationStepEntry info_step_entry() { return {{"UtilsStep", "InfoStep"}, step_parameters({}), make}; }

}  // namespace structmd
