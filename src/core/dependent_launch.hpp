#pragma once
// Programmatic dependent launch (Hopper and newer), for every kernel of the CUDA backend and the
// traversal kernels written beside their functors (transverser/all_pairs_traversal.hpp). Free of the
// standard library, so that kernels compiled at run time include it too.
#include "core/hd.hpp"

namespace structmd {

#if defined(__CUDACC__)
// In a step graph each kernel is a programmatic dependent of the one before (step_graphs.cuh): it is
// scheduled while that one still runs and waits here, before touching memory, until it has finished
// and its writes are visible. It then lets the next kernel be scheduled in turn, so a chain of small
// kernels does not pay a launch between each two. Outside such a graph both are no-ops.
__device__ __forceinline__ void follow_previous_kernel() {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
    asm volatile("griddepcontrol.wait;" ::: "memory");
    asm volatile("griddepcontrol.launch_dependents;" :::);
#endif
}
#endif

}  // namespace structmd
