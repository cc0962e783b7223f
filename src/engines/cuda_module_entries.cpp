// The one symbol libstructmd_cuda.so exports (engines/cuda_module.hpp): its CUDA engines and device queries.
#include "engines/cuda_module.hpp"
#include "engines/devices.hpp"
#include "engines/plugin_abi.hpp"

extern "C" __attribute__((visibility("default"))) const structmd::CudaModuleEntries* structmd_cuda_module_entries() {
    using namespace structmd;
    static const CudaModuleEntries entries{
        STRUCTMD_PLUGIN_BUILD,
        &usable_gpu_count,
        &gpu_name,
#ifdef STRUCTMD_WITH_SINGLE
        &make_cuda_engine_single,
#else
        nullptr,
#endif
#ifdef STRUCTMD_WITH_MIXED
        &make_cuda_engine_mixed,
#else
        nullptr,
#endif
#ifdef STRUCTMD_WITH_DOUBLE
        &make_cuda_engine_double,
#else
        nullptr,
#endif
    };
    return &entries;
}
