// Engine<CpuBackend, float>, in a translation unit of its own so the two precisions compile in
// parallel.
#include "backends/backend_engines.hpp"
#include "backends/cpu/cpu_backend.hpp"
#include "simulation/engine.hpp"

namespace structmd {

std::unique_ptr<Simulation> make_cpu_engine_single(int threads, SimulationSpec spec, const Logger& log) {
    return std::make_unique<Engine<CpuBackend, float>>(std::move(spec), log, threads);
}

}  // namespace structmd
