// Engine<CpuBackend, double, float>: state and sums in double, pair terms evaluated in single; in a
// translation unit of its own so the precisions compile in parallel.
#include "backends/backend_engines.hpp"
#include "backends/cpu/cpu_backend.hpp"
#include "simulation/engine.hpp"

namespace structmd {

std::unique_ptr<Simulation> make_cpu_engine_mixed(int threads, SimulationSpec spec, const Logger& log) {
    return std::make_unique<Engine<CpuBackend, double, float>>(std::move(spec), log, threads);
}

}  // namespace structmd
