#pragma once
// ["TransverserMeasure","Plugin"] (structmd's own): every firing, runs a transverser that a loaded
// plugin registered (docs/plugins.md, "Transversers"), as structmd_traverse runs it, and writes each
// particle's values (transverser_measure.hpp says the file's format). "transverser" names it,
// "transverserParameters" holds its named parameters, "cutOff" > 0 traverses the pairs closer than
// it over a neighbour list and 0 (the default) every pair; the group's particles take part, both of
// a pair. The name and the parameters are checked at load, against the handle's plugins.
#include <cstdint>
#include <string>
#include <vector>

#include "simulation/transverser_call.hpp"
#include "steps/simulation_step_registry.hpp"
#include "steps/transverser_measure.hpp"

namespace structmd {

class PluginTransverserMeasure final : public TransverserMeasure {
public:
    PluginTransverserMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                             TransverserCall call, std::vector<int64_t> ids);

private:
    void traverse(Simulation& sim, double* perParticle) override;

    TransverserCall call_;
};

SimulationStepEntry plugin_transverser_measure_entry();

}  // namespace structmd
