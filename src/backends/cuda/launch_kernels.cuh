#pragma once
// The two kernels every launch of the CUDA backend goes through: f(i) for each item, and f(i, lanes)
// with several threads per item. Free of the standard library, so that kernels compiled at run time
// (runtime_compiler.hpp) instantiate these same templates.
#include "core/dependent_launch.hpp"
#include "core/hd.hpp"
#include "core/lanes.hpp"

namespace structmd {

// How many blocks of 128 threads per multiprocessor a launch of F is compiled for: F's own
// kResidentBlocks where it names one (a kernel whose registers matter more than its resident warps,
// or the other way round), otherwise the launch's default. Written without <type_traits> for the
// same reason as the rest of this file.
template <class T>
struct VoidOf {
    using type = void;
};
template <class F, int kDefault, class = void>
struct ResidentBlocks {
    static constexpr int value = kDefault;
};
template <class F, int kDefault>
struct ResidentBlocks<F, kDefault, typename VoidOf<decltype(F::kResidentBlocks)>::type> {
    static constexpr int value = F::kResidentBlocks;
};

template <class F>
__global__ void for_each_kernel(int64_t n, F f) {
    follow_previous_kernel();
    const int64_t i = static_cast<int64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
    if (i < n) f(i);
}

// Item i gets `lanes` consecutive threads (a power of two dividing the warp), so the lanes of an
// item share a warp and can exchange values through shuffles.
// 128 threads and by default 8 blocks per multiprocessor: at most 64 registers, so that the pair
// kernel keeps half of the device's warps resident.
template <class F>
__global__ void __launch_bounds__(128, (ResidentBlocks<F, 8>::value)) for_each_lanes_kernel(int64_t n, int lanes, F f) {
    follow_previous_kernel();
    const int64_t thread = static_cast<int64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
    const int64_t i = thread / lanes;
    if (i >= n) return;
    Lanes group;
    group.count = lanes;
    group.lane = static_cast<int>(thread % lanes);
    group.warpLane = static_cast<int>(threadIdx.x % 32);
    group.mask = lanes == 32 ? 0xffffffffu : ((1u << lanes) - 1u) << (group.warpLane - group.lane);
    f(i, group);
}

// for_each_lanes_kernel where every item has one lane (a large system): no shuffles and fewer values
// live, so by default 12 blocks per multiprocessor (at most 40 registers) fit. The LJ pair kernel at
// a million particles then keeps about 3/4 of the warps resident instead of half and runs 20% faster;
// with several lanes the same cap spills and cost 2-7% (docs/benchmarks.md).
template <class F>
__global__ void __launch_bounds__(128, (ResidentBlocks<F, 12>::value)) for_each_lone_lane_kernel(int64_t n, int, F f) {
    follow_previous_kernel();
    const int64_t i = static_cast<int64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
    if (i >= n) return;
    Lanes single;
    single.warpLane = static_cast<int>(threadIdx.x % 32);
    single.mask = 1u << single.warpLane;
    f(i, single);
}

}  // namespace structmd
