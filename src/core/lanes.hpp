#pragma once
// Lanes: the threads that work together on one item (a particle's neighbours). On the GPU they are
// a power-of-two segment of a warp, so a small system still fills the device and a long neighbour
// loop is split among several threads; on the CPU an item has one lane and every operation here
// is the identity. Code written against Lanes is the same source for both backends.
#include "core/hd.hpp"
#include "core/vec.hpp"

namespace structmd {

// How many lanes a backend with lanes (the GPU) gives each item. kNeighbourSum: the items' threads
// fill at most half the device, so each lane walks several neighbours with their loads in flight
// (the pair kernels: 8 lanes per particle at 10,976 particles ran 9% faster than the 32 that fill
// the device; docs/benchmarks.md). kFillDevice: lanes until the items' threads fill the device
// (the list build, whose ~500 candidate tests per particle are arithmetic, the scans of cells, and
// the spreads onto grid lines, whose lanes each repeat a particle's weights: owns_point below).
// kWarp: a whole warp per item (a cluster of particles and its partner clusters, whose lanes share
// out the pairs of the clusters).
enum class LaneSizing { kNeighbourSum, kFillDevice, kWarp };

// Threads a block of the GPU's kernels over items: what their launch bounds assume, and what a
// kernel sizing shared memory by thread counts on.
constexpr int kBlockThreads = 128;

struct Lanes {
    int lane = 0;        // this thread's rank within the item's lanes
    int count = 1;       // lanes per item: a power of two, at most 32
    int warpLane = 0;    // this thread's rank within its warp
    unsigned mask = 1u;  // the item's lanes within the warp

    SMD_HD SMD_INLINE bool leader() const { return lane == 0; }

    // The sum of v over the item's lanes, in every lane; a fixed butterfly, so the result does not
    // depend on thread timing.
    template <class T>
    SMD_HD SMD_INLINE T sum(T v) const {
#if defined(__CUDA_ARCH__)
        for (int offset = count / 2; offset > 0; offset /= 2) v += __shfl_xor_sync(mask, v, offset, count);
#endif
        return v;
    }
    template <class R>
    SMD_HD SMD_INLINE Vec3<R> sum(Vec3<R> v) const {
        return {sum(v.x), sum(v.y), sum(v.z)};
    }
    template <class R>
    SMD_HD SMD_INLINE Tensor3<R> sum(const Tensor3<R>& w) const {
        return {sum(w.xx), sum(w.xy), sum(w.xz), sum(w.yx), sum(w.yy), sum(w.yz), sum(w.zx), sum(w.zy), sum(w.zz)};
    }

    // The sum of v over the lanes whose rank has the same remainder modulo `stride` (a power of two
    // below count), in each of them: lanes that share out one item's work by rank / stride.
    template <class T>
    SMD_HD SMD_INLINE T sum_across(T v, int stride) const {
#if defined(__CUDA_ARCH__)
        for (int offset = stride; offset < count; offset *= 2) v += __shfl_xor_sync(mask, v, offset, count);
#else
        (void)stride;  // one lane on the host: nothing to sum across
#endif
        return v;
    }
    template <class R>
    SMD_HD SMD_INLINE Vec3<R> sum_across(Vec3<R> v, int stride) const {
        return {sum_across(v.x, stride), sum_across(v.y, stride), sum_across(v.z, stride)};
    }
    template <class R>
    SMD_HD SMD_INLINE Tensor3<R> sum_across(const Tensor3<R>& w, int stride) const {
        return {sum_across(w.xx, stride), sum_across(w.xy, stride), sum_across(w.xz, stride),
                sum_across(w.yx, stride), sum_across(w.yy, stride), sum_across(w.yz, stride),
                sum_across(w.zx, stride), sum_across(w.zy, stride), sum_across(w.zz, stride)};
    }

    // v as lane `from` of the item holds it (every lane of the item must take part).
    SMD_HD SMD_INLINE int from_lane(int v, int from) const {
#if defined(__CUDA_ARCH__)
        return __shfl_sync(mask, v, from, count);
#else
        (void)from;
        return v;
#endif
    }

    // v combined over the item's lanes by accumulate(total, other), in every lane: the butterfly of
    // sum() for any trivially copyable T (a transverser's Compute, transverser/transverser.hpp),
    // exchanged word by word. accumulate must be associative and commutative for the result not to
    // depend on how the items were split among lanes.
    template <class T, class Accumulate>
    SMD_HD SMD_INLINE T combine(T v, const Accumulate& accumulate) const {
#if defined(__CUDA_ARCH__)
        constexpr int words = (sizeof(T) + sizeof(int) - 1) / sizeof(int);
        for (int offset = count / 2; offset > 0; offset /= 2) {
            int mine[words] = {};
            copy_bytes(reinterpret_cast<char*>(mine), reinterpret_cast<const char*>(&v), sizeof(T));
            int theirs[words];
            for (int w = 0; w < words; ++w) theirs[w] = __shfl_xor_sync(mask, mine[w], offset, count);
            T other;
            copy_bytes(reinterpret_cast<char*>(&other), reinterpret_cast<const char*>(theirs), sizeof(T));
            accumulate(v, other);
        }
#else
        (void)accumulate;
#endif
        return v;
    }

    // memcpy without the standard library (kernels compiled at run time have none).
    static SMD_HD SMD_INLINE void copy_bytes(char* to, const char* from, unsigned long bytes) {
        for (unsigned long b = 0; b < bytes; ++b) to[b] = from[b];
    }

    // The sum of v over the lanes below this one, and (in total) over all the item's lanes.
    SMD_HD SMD_INLINE int exclusive_sum(int v, int& total) const {
#if defined(__CUDA_ARCH__)
        int inclusive = v;
        for (int offset = 1; offset < count; offset *= 2) {
            const int below = __shfl_up_sync(mask, inclusive, offset, count);
            if (lane >= offset) inclusive += below;
        }
        total = __shfl_sync(mask, inclusive, count - 1, count);
        return inclusive - v;
#else
        total = v;
        return 0;
#endif
    }

    // For a flag raised by some lanes: how many lanes below this one raised it, and (in total) how
    // many raised it, so each can write its entry after the others without atomics.
    SMD_HD SMD_INLINE int rank_among(bool flag, int& total) const {
#if defined(__CUDA_ARCH__)
        if (count == 1) {  // a ballot of one would still make the warp's threads wait for each other
            total = flag ? 1 : 0;
            return 0;
        }
        const unsigned raised = __ballot_sync(mask, flag) & mask;
        total = __popc(raised);
        return __popc(raised & ((1u << warpLane) - 1u));
#else
        total = flag ? 1 : 0;
        return 0;
#endif
    }
};

// Whether `lanes` owns point x (0 <= x) of a grid line that one item spreads onto: the lane of rank
// x modulo the lane count clears the point and sums every term into it. Each point thus takes its
// terms in the order of the loops that spread them, on any power-of-two number of lanes (one on the
// CPU), and no two lanes write one point (no atomics). With about ten particles' kernels on a point,
// one thread per line left the device mostly idle (docs/benchmarks.md); the lanes share out a
// line's points instead.
SMD_HD SMD_INLINE bool owns_point(const Lanes& lanes, int x) { return (x & (lanes.count - 1)) == lanes.lane; }

}  // namespace structmd
