#pragma once
// A transverser (transverser.hpp) over all pairs of particles, without a cutoff (UAMMD's NBody): each
// particle of the group visits every other particle of the group, its periodic image nearest to it
// in a periodic box (an open box: lengths of infinity, where the nearest image is the particle), and
// of its batch (independent systems overlaid in one box, as the neighbour lists keep them apart). The
// cost is n^2, for interactions of no finite range (gravity, unscreened Coulomb in an open box) and
// for systems small enough that a list does not pay. Free of the standard library, as the other
// traversal.
//
// On the GPU the traversal runs through all_pairs_tiles_kernel (UAMMD's NBody, after Nyland, Harris
// and Prins, GPU Gems 3, ch. 31): the threads of a block load a tile of kAllPairsTile particles
// (position, Info, batch, membership) into shared memory together, and every particle of the block
// reads its partners from there. Global memory then serves each particle once per block instead of
// once per particle. traverse_all_pairs launches it where each particle has a thread of its own (a
// large system); elsewhere the functor runs as it is, each particle's partners split among lanes.
#include "core/box.hpp"
#include "core/dependent_launch.hpp"
#include "core/hd.hpp"
#include "core/lanes.hpp"
#include "core/vec.hpp"
#include "transverser/transverser.hpp"

namespace structmd {

#if defined(__CUDACC__)
// Tiles of one block's width: the CUDA backend's blocks of 128 threads.
constexpr int kAllPairsTile = 128;
#endif

template <class Transverser, class R>
struct AllPairsTraversal {
    Transverser transverser;
    const Real4<R>* positions;  // by particle (w: the type)
    int64_t count;
    Box<R> box;
    const uint8_t* group;  // by particle; null: every particle takes part
    const int* batch;      // by particle; null: one batch. Particles of different batches never pair

    SMD_HD void operator()(int64_t item, Lanes lanes) const {
        const int i = static_cast<int>(item);
        if (group && !group[i]) return;
        const Transverser& t = transverser;
        const Real4<R> pi = positions[i];
        const auto infoI = t.info(i);
        const int batchI = batch ? batch[i] : 0;
        auto total = t.zero();
        // The lanes take turns through the particles, so each load is shared by a warp's items.
        for (int64_t j = lanes.lane; j < count; j += lanes.count) {
            if (j == item || (group && !group[j]) || (batch && batch[j] != batchI)) continue;
            const PairFrame<R> pair = pair_frame(pi, positions[j], box);
            t.accumulate(total, t.compute(pair.first, pair.second, infoI, t.info(static_cast<int>(j))));
        }
        total = lanes.combine(total, [&](decltype(total)& a, const decltype(total)& b) { t.accumulate(a, b); });
        if (lanes.leader()) t.set(i, total);
    }

#if defined(__CUDACC__)
    // What a tile keeps of partner j.
    struct TileEntry {
        Real4<R> position;
        typename Transverser::Info info;
        int batch;
        int member;
    };

    // The block's items (item >= count and non-members included: every thread of the block loads its
    // share of each tile and meets each barrier); `tile` holds kAllPairsTile entries, one per thread.
    __device__ void in_tiles(int64_t item, Lanes lanes, TileEntry* tile) const {
        const Transverser& t = transverser;
        const bool active = item < count && (!group || group[item]);
        const int i = active ? static_cast<int>(item) : 0;
        const Real4<R> pi = positions[i];
        const typename Transverser::Info infoI = t.info(i);
        const int batchI = batch ? batch[i] : 0;
        auto total = t.zero();
        for (int64_t base = 0; base < count; base += kAllPairsTile) {
            const int64_t j = base + threadIdx.x;
            if (j < count) {
                const int at = static_cast<int>(j);
                tile[threadIdx.x] = TileEntry{positions[at], t.info(at), batch ? batch[at] : 0, !group || group[at]};
            }
            __syncthreads();
            const int64_t left = count - base;
            const int inTile = left < kAllPairsTile ? static_cast<int>(left) : kAllPairsTile;
            if (active)
                for (int k = lanes.lane; k < inTile; k += lanes.count) {
                    const TileEntry& partner = tile[k];
                    if (base + k == item || !partner.member || partner.batch != batchI) continue;
                    const PairFrame<R> pair = pair_frame(pi, partner.position, box);
                    t.accumulate(total, t.compute(pair.first, pair.second, infoI, partner.info));
                }
            __syncthreads();
        }
        if (!active) return;
        total = lanes.combine(total, [&](decltype(total)& a, const decltype(total)& b) { t.accumulate(a, b); });
        if (lanes.leader()) t.set(i, total);
    }
#endif
};

#if defined(__CUDACC__)
// The launch of for_each_lanes_kernel (items of `lanes` consecutive threads), with the tile in
// shared memory; blocks of kAllPairsTile threads.
template <class Transverser, class R>
__global__ void __launch_bounds__(kAllPairsTile) all_pairs_tiles_kernel(int64_t n, int lanes,
                                                                        AllPairsTraversal<Transverser, R> f) {
    using Entry = typename AllPairsTraversal<Transverser, R>::TileEntry;
    // Raw storage: an Info may have constructors, which shared variables cannot run.
    __shared__ alignas(16) unsigned char storage[kAllPairsTile * sizeof(Entry)];
    follow_previous_kernel();
    const int64_t thread = static_cast<int64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
    Lanes group;
    group.count = lanes;
    group.lane = static_cast<int>(thread % lanes);
    group.warpLane = static_cast<int>(threadIdx.x % 32);
    group.mask = lanes == 32 ? 0xffffffffu : ((1u << lanes) - 1u) << (group.warpLane - group.lane);
    f.in_tiles(thread / lanes, group, reinterpret_cast<Entry*>(storage));
}
#endif

#if SMD_HOST_CODE
// Whether the GPU runs all pairs of n particles through the tiles: where each particle has one lane.
// With several lanes a tile holds only a few pairs per lane between two barriers, and the lanes'
// loads through the cache were faster: gravity at 4,096 and 32,768 particles on an H200 ran 15-50%
// slower in tiles, at 131,072 (one lane) 15% faster (docs/benchmarks.md).
template <class B>
bool all_pairs_in_tiles(const B& backend, int64_t n) {
    return backend.lanes_for(n, LaneSizing::kNeighbourSum) == 1;
}

// Runs `traversal` for particles [0, n): through the tiles where the unit is compiled for the GPU, the
// backend launches kernels by address (the CUDA backend) and each particle has one lane, else through
// the backend's lanes.
template <class B, class Transverser, class R>
void traverse_all_pairs(const B& backend, int64_t n, const AllPairsTraversal<Transverser, R>& traversal) {
#if defined(__CUDACC__)
    if constexpr (B::compiles_at_run_time) {
        if (!all_pairs_in_tiles(backend, n)) {
            backend.for_each_lanes(n, traversal);
            return;
        }
        backend.for_each_lanes_compiled(reinterpret_cast<const void*>(&all_pairs_tiles_kernel<Transverser, R>), n,
                                        traversal);
        return;
    }
#endif
    backend.for_each_lanes(n, traversal);
}
#endif

}  // namespace structmd
