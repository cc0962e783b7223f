#include "steps/afm_measure.hpp"

#include <memory>

#include "core/error.hpp"

namespace structmd {

namespace {

std::string header(size_t tips, bool verbose) {
    std::string text = "#step time";
    for (size_t t = 0; t < tips; ++t) {
        const std::string k = "_" + std::to_string(t);
        text += verbose ? " chip" + k + " tip" + k + " deflection" + k + " tipForce" + k + " sampleForce" + k + " F" + k
                        : " X" + k + " F" + k;
    }
    return text;
}

double total_z_force(Simulation& sim, const std::vector<int64_t>& ids) {
    std::vector<double> f(3 * ids.size());
    sim.get_forces_of(ids.data(), static_cast<int64_t>(ids.size()), f.data());
    double z = 0.0;
    for (size_t k = 0; k < ids.size(); ++k) z += f[3 * k + 2];
    return z;
}

}  // namespace

AfmMeasure::AfmMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                       bool verbose, std::vector<Tip> tips)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), header(tips.size(), verbose)),
      verbose_(verbose),
      tips_(std::move(tips)) {}

void AfmMeasure::run(Simulation& sim) {
    const int64_t step = sim.current_step();
    std::FILE* out = file_.stream();
    std::fprintf(out, "%lld %.17g", static_cast<long long>(step), sim.current_time());
    for (const Tip& tip : tips_) {
        double z[3];
        sim.get_positions_of(&tip.id, 1, z);
        const double chip = tip.afm.chip_at(step).z;
        const double deflection = z[2] - chip;
        const double force = tip.afm.K.z * deflection;
        if (verbose_)
            std::fprintf(out, " %.17g %.17g %.17g %.17g %.17g %.17g", chip, z[2], deflection,
                         total_z_force(sim, {tip.id}), total_z_force(sim, tip.sample), force);
        else
            std::fprintf(out, " %.17g %.17g", z[2] - tip.radius, force);
    }
    std::fprintf(out, "\n");
    file_.flush();
}

std::vector<AfmMeasure::Tip> read_afm_tips(const StepInput& in) {
    const AfmConfig* config = nullptr;
    for (const ExternalSpec& external : in.forceField.externals)
        if (external.key.cls == "AFM" && (config = dynamic_cast<const AfmConfig*>(external.config.get()))) break;
    if (!config)
        throw input_error(in.path + ".type", "reads an AFM experiment: the input has no [\"AFM\", ...] entry");
    std::vector<AfmMeasure::Tip> tips;
    const size_t rows = (config->start.size() - 1) / 2;
    for (size_t row = 0; row < rows; ++row) {
        const int64_t id = config->members[config->start[2 * row]];
        if (!in.members.empty() && !in.members[id]) continue;
        // Only the chip and its spring are read; every tip's schema has SphericalTip's epsilon and sigma.
        AfmMeasure::Tip tip{id, in.system.radius[id], afm_row_params<SphericalTipPotential, double>(*config, row), {}};
        tip.sample.assign(config->members.begin() + config->start[2 * row + 1],
                          config->members.begin() + config->start[2 * row + 2]);
        tips.push_back(std::move(tip));
    }
    if (tips.empty()) throw input_error(in.parameters.path("group"), "the group holds no AFM tip");
    return tips;
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    return std::make_unique<AfmMeasure>(in.name, in.interval(), in.start(), in.end(),
                                        in.parameters.text("outputFilePath"), in.parameters.flag("verbose"),
                                        read_afm_tips(in));
}

}  // namespace

SimulationStepEntry afm_measure_entry() {
    return {{"ExperimentMeasures", "AFMMeasure"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr},
                             {"verbose", StepValue::flag, false},
                             {"tipType", StepValue::text, "TIP", Must::be_finite, "",
                              "accepted and unused: each row of the AFM entry names its tip"}}),
            make};
}

}  // namespace structmd
