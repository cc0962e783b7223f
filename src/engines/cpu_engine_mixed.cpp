// Engine<CpuBackend, double, float> (mixed precision), in a translation unit of its own.
#include "engines/cpu_backend_unit.hpp"
#include "engines/engine_instances.hpp"
#include "simulation/engine.hpp"

namespace structmd {

std::unique_ptr<LocalEngine> make_cpu_engine_mixed(int threads, SimulationSpec spec,
                                                  const ForceFieldComponents& components, const Logger& log) {
    return std::make_unique<Engine<CpuBackend, double, float>>(std::move(spec), components, log, threads);
}

}  // namespace structmd
