// Engine<CudaBackend, double, float>: state and sums in double, pair terms evaluated in single; in
// a translation unit of its own so the precisions compile in parallel.
#include "backends/backend_engines.hpp"
#include "backends/cuda/cuda_backend.cuh"
#include "simulation/engine.hpp"

namespace structmd {

std::unique_ptr<Simulation> make_cuda_engine_mixed(int device, SimulationSpec spec, const Logger& log) {
    return std::make_unique<Engine<CudaBackend, double, float>>(std::move(spec), log, device);
}

}  // namespace structmd
