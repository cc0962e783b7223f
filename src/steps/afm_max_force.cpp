#include "steps/afm_max_force.hpp"

#include <algorithm>
#include <memory>

namespace structmd {

AfmMaxForce::AfmMaxForce(std::string name, int64_t interval, int64_t start, int64_t end, double maxForce,
                         std::vector<AfmMeasure::Tip> tips)
    : SimulationStep(name, interval, start, end),
      maxForce_(maxForce),
      tips_(std::move(tips)),
      reached_(tips_.size(), false) {}

void AfmMaxForce::run(Simulation& sim) {
    const int64_t step = sim.current_step();
    const auto all = [this] { return std::all_of(reached_.begin(), reached_.end(), [](bool reached) { return reached; }); };
    if (all()) return;
    for (size_t t = 0; t < tips_.size(); ++t) {
        if (reached_[t]) continue;
        double r[3];
        sim.get_positions_of(&tips_[t].id, 1, r);
        const double force = tips_[t].afm.K.z * (r[2] - tips_[t].afm.chip_at(step).z);
        reached_[t] = force >= maxForce_;
    }
    if (all()) sim.request_stop(name());
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    return std::make_unique<AfmMaxForce>(in.name, in.interval(), in.start(), in.end(), in.parameters.number("maxForce"),
                                         read_afm_tips(in));
}

}  // namespace

SimulationStepEntry afm_max_force_entry() {
    return {{"FlowControl", "AFMMaxForce"},
            step_parameters({{"maxForce", StepValue::number, nullptr, Must::be_finite, "force",
                              "the cantilever force K (z_tip - z_chip) every tip must reach"},
                             {"tipType", StepValue::text, "TIP", Must::be_finite, "",
                              "accepted and unused: each row of the AFM entry names its tip"}}),
            make};
}

}  // namespace structmd
