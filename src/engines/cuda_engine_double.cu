// Engine<CudaBackend, double> (double precision), in a translation unit of its own.
#include "engines/cuda_backend_unit.cuh"
#include "engines/engine_instances.hpp"
#include "simulation/engine.hpp"

namespace structmd {

std::unique_ptr<LocalEngine> make_cuda_engine_double(int device, SimulationSpec spec,
                                                    const ForceFieldComponents& components, const Logger& log) {
    return std::make_unique<Engine<CudaBackend, double>>(std::move(spec), components, log, device);
}

}  // namespace structmd
