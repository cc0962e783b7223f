#pragma once
// One factory per (backend, precision), each defined in a translation unit of its own
// (cpu_engine_*.cpp, cuda_engine_*.cu) so the six compile in parallel; make_engine.cpp picks one.
// A build limited by STRUCTMD_PRECISIONS compiles, and make_engine.cpp calls, only its precisions'.
#include <memory>

#include "core/logger.hpp"
#include "forcefield/component_set.hpp"
#include "simulation/local_engine.hpp"
#include "simulation/simulation_spec.hpp"

namespace structmd {

std::unique_ptr<LocalEngine> make_cpu_engine_single(int threads, SimulationSpec spec,
                                                   const ForceFieldComponents& components, const Logger& log);
std::unique_ptr<LocalEngine> make_cpu_engine_mixed(int threads, SimulationSpec spec,
                                                  const ForceFieldComponents& components, const Logger& log);
std::unique_ptr<LocalEngine> make_cpu_engine_double(int threads, SimulationSpec spec,
                                                   const ForceFieldComponents& components, const Logger& log);
std::unique_ptr<LocalEngine> make_cuda_engine_single(int device, SimulationSpec spec,
                                                    const ForceFieldComponents& components, const Logger& log);
std::unique_ptr<LocalEngine> make_cuda_engine_mixed(int device, SimulationSpec spec,
                                                   const ForceFieldComponents& components, const Logger& log);
std::unique_ptr<LocalEngine> make_cuda_engine_double(int device, SimulationSpec spec,
                                                    const ForceFieldComponents& components, const Logger& log);

}  // namespace structmd
