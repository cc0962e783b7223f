#include "backends/backend_engines.hpp"
#include "backends/cpu/cpu_backend.hpp"
#include "simulation/engine.hpp"

namespace structmd {

std::unique_ptr<Simulation> make_cpu_engine(bool doublePrecision, int threads, SimulationSpec spec,
                                            const Logger& log) {
    if (doublePrecision) return std::make_unique<Engine<CpuBackend, double>>(std::move(spec), log, threads);
    return std::make_unique<Engine<CpuBackend, float>>(std::move(spec), log, threads);
}

int cpu_default_threads() { return omp_get_max_threads(); }

}  // namespace structmd
