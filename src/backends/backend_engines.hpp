#pragma once
// Entry points of the compiled backends: each instantiates Engine<Backend, state real, pair real>
// for single, mixed and double precision in its own translation unit (the CUDA one compiled by nvcc), so nothing else includes backend headers.
#include <memory>
#include <string>

#include "core/logger.hpp"
#include "simulation/simulation.hpp"
#include "simulation/simulation_spec.hpp"

namespace structmd {

// precision: "single", "mixed" or "double" (validated by the options).
std::unique_ptr<Simulation> make_cpu_engine(const std::string& precision, int threads, SimulationSpec spec, const Logger& log);
std::unique_ptr<Simulation> make_cpu_engine_single(int threads, SimulationSpec spec, const Logger& log);
std::unique_ptr<Simulation> make_cpu_engine_mixed(int threads, SimulationSpec spec, const Logger& log);
std::unique_ptr<Simulation> make_cpu_engine_double(int threads, SimulationSpec spec, const Logger& log);
int cpu_default_threads();

// Present only in builds with the CUDA backend (STRUCTMD_HAVE_CUDA).
std::unique_ptr<Simulation> make_cuda_engine(const std::string& precision, int device, SimulationSpec spec, const Logger& log);
std::unique_ptr<Simulation> make_cuda_engine_single(int device, SimulationSpec spec, const Logger& log);
std::unique_ptr<Simulation> make_cuda_engine_mixed(int device, SimulationSpec spec, const Logger& log);
std::unique_ptr<Simulation> make_cuda_engine_double(int device, SimulationSpec spec, const Logger& log);
int cuda_device_count();
std::string cuda_device_name(int device);

}  // namespace structmd
