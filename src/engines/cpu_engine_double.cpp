// Engine<CpuBackend, double> (double precision), in a translation unit of its own.
#include "backends/cpu/cpu_backend.hpp"
#include "backends/cpu/cpu_cholesky.hpp"
#include "backends/cpu/cpu_fft.hpp"
#include "engines/engine_instances.hpp"
#include "simulation/engine.hpp"

namespace structmd {

std::unique_ptr<Simulation> make_cpu_engine_double(int threads, SimulationSpec spec,
                                                   const ForceFieldComponents& components, const Logger& log) {
    return std::make_unique<Engine<CpuBackend, double>>(std::move(spec), components, log, threads);
}

}  // namespace structmd
