#include "steps/plugin_transverser_measure.hpp"

#include <memory>

#include "forcefield/component_set.hpp"
#include "input/tracked_node.hpp"

namespace structmd {

PluginTransverserMeasure::PluginTransverserMeasure(std::string name, int64_t interval, int64_t start, int64_t end,
                                                   std::string outputPath, TransverserCall call,
                                                   std::vector<int64_t> ids)
    : TransverserMeasure(std::move(name), interval, start, end, std::move(outputPath), call.values, std::move(ids)),
      call_(std::move(call)) {}

void PluginTransverserMeasure::traverse(Simulation& sim, double* perParticle) {
    sim.probes().traverse(call_, perParticle);
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    if (!in.components)
        throw Error(STRUCTMD_ERR_UNSUPPORTED, in.path + ": [\"TransverserMeasure\",\"Plugin\"] runs a plugin's "
                                                        "transverser on one engine; it is not supported under replicas "
                                                        "or batches spread over ranks");
    const std::string name = in.parameters.text("transverser");
    if (!in.components->transverser_source(name))
        throw input_error(in.parameters.path("transverser"), in.components->unknown_transverser(name));
    // The object is read in a tracking of its own, so that a key it should not hold is named by its path.
    auto state = std::make_shared<input::TrackingState>();
    state->document = in.parameters.object("transverserParameters");
    const input::TrackedNode given(state, &state->document, in.parameters.path("transverserParameters"));
    TransverserCall call = make_transverser_call(*in.components, name, given, given.path(), in.parameters.number("cutOff"));
    call.group = in.parameters.text("group");
    call.path = in.parameters.path("group");
    return std::make_unique<PluginTransverserMeasure>(in.name, in.interval(), in.start(), in.end(),
                                                      in.parameters.text("outputFilePath"), std::move(call),
                                                      in.member_ids());
}

}  // namespace

SimulationStepEntry plugin_transverser_measure_entry() {
    return {{"TransverserMeasure", "Plugin"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr},
                             {"transverser", StepValue::text, nullptr, Must::be_finite, "",
                              "the name a loaded plugin registered the transverser under"},
                             {"transverserParameters", StepValue::object, nlohmann::json::object(), Must::be_finite,
                              "", "its named parameters; absent ones take their defaults"},
                             {"cutOff", StepValue::number, 0.0, Must::be_non_negative, "length",
                              "0: all pairs"}}),
            make};
}

}  // namespace structmd
