#pragma once
// The CUDA backend as a module of its own, libstructmd_cuda.so beside libstructmd (a build with
// STRUCTMD_CUDA_MODULE, as pip's): libstructmd then links no CUDA library, and loads the module
// (cuda_module_loader.cpp) only when the CUDA backend is asked for or probed, so that the CPU backend
// works where the CUDA libraries are absent. The module exports one C function that returns its
// entries; both sides are compiled in one build from these headers, and the loader refuses a module
// of another build (the plugins' build string, engines/plugin_abi.hpp), so C++ types may cross.
#include <memory>
#include <string>

#include "engines/engine_instances.hpp"

namespace structmd {

using MakeCudaEngineFn = std::unique_ptr<LocalEngine> (*)(int device, SimulationSpec spec,
                                                          const ForceFieldComponents& components, const Logger& log);

struct CudaModuleEntries {
    const char* build;  // STRUCTMD_PLUGIN_BUILD of the module
    int (*usable_gpu_count)();
    std::string (*gpu_name)(int device);
    // Null for a precision the build lacks (STRUCTMD_PRECISIONS).
    MakeCudaEngineFn make_engine_single;
    MakeCudaEngineFn make_engine_mixed;
    MakeCudaEngineFn make_engine_double;
};

inline constexpr const char* kCudaModuleFile = "libstructmd_cuda.so";
inline constexpr const char* kCudaModuleEntriesSymbol = "structmd_cuda_module_entries";
using CudaModuleEntriesFn = const CudaModuleEntries* (*)();

}  // namespace structmd
