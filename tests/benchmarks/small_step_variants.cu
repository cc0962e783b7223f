// nvcc -O3 -std=c++17 -arch=sm_90 -Isrc -Iinclude -o ssv tests/benchmarks/small_step_variants.cu
//
// Small-step design study for issue 33: how fast can a whole velocity-Verlet NVE step of the LJ
// liquid be at small N on one GPU, and which design gets there. Standalone (no engine code), so
// each variant is the bare step. The liquid: fcc at density 0.8442 (4 k^3 particles), jittered,
// velocities at T = 1.44 with zero total momentum, rc 2.5, list radius 2.8 (skin 0.3), dt 0.005,
// mass 1, single precision. Every variant keeps a full Verlet list built on the device from a cell
// list, rebuilt when a particle has moved more than skin/2 since the last build; the builds are
// part of every timed loop and use the same kernels' code (bin, sort each cell's members by index
// so that the lists do not depend on thread timing, a warp per particle writing its list in cell
// order through ballots). Variants:
//   chain        what the engine does today: a graph of 50 steps, each a chain of kernels (clock,
//                drift with the displacement check, a one-thread kernel setting the condition,
//                the list build in an IF conditional node, the pair kernel, the closing kick), the
//                edges between consecutive kernels programmatic (dependent launch) as in the
//                engine. Lanes per particle as the engine sizes them (kNeighbourSum, core/lanes.hpp).
//                The pair kernel stores the forces (nothing to clear) and the particles keep their
//                order (sorted by cell once, at the start), so the drift has no slot copy to make.
//   chain-g16    chain in graphs of 16 steps, the engine's kStepsPerGraph: what the graph length
//                costs at small N. A run that is not a multiple of 16 ends on a shorter graph,
//                captured before it starts (the timed 2000 steps are 125 whole graphs).
//   fused-L      one kernel per step at L lanes per particle: the pair kernel reads x(n) from one
//                buffer and each particle's epilogue applies the closing kick of step n, the opening
//                kick of step n+1 and the drift, writing x(n+1) to the other buffer; the last block
//                to finish sets the IF node's condition from the displacement flag (no setter
//                kernel). Graphs of 50 steps, the two buffers swapping from node to node.
//   persistent-L one cooperative launch for all the steps, phases separated by grid.sync(): the
//                fused step, then, when the flag read by every block after the barrier says so,
//                the three build phases. The grid: what is co-resident, at most what the pair
//                phase needs.
// Two more keep no list: the pair phase reads cell tiles from shared memory. The particles are kept
// sorted by list cell (the same cells, edge >= 2.8); the build (same half-skin criterion and flag
// logic) wraps the positions, bins them, scans the counts into cell starts, and moves positions,
// velocities, build positions and original ids into cell order (by original id within a cell, so
// that no sum depends on the binning atomics). A block of 128 threads takes a (home cell, part):
// it loads the 27 cells' positions into shared memory, each cell shifted by the periodic image that
// puts it beside the home cell (the drift does not wrap between builds, so that shift stays right),
// then L lanes per home member go over the ~500 candidates, keep those within rc (re-tested every
// step; the skin only decides when to re-sort), combine by shuffles and take the fused epilogue.
// A cell's members go in rounds of 128 / L, the rounds shared among `parts` blocks per cell
// (enough that a cell of average size takes one round), so small liquids still fill the device.
//   cells-fused-L       fused's graph (one kernel per step, the re-sort in the IF node) over tiles.
//   cells-persistent-L  persistent's cooperative kernel over tiles; the re-sort takes three phases.
// Two more over cells of half the edge (>= 1.4), in a system of their own, re-sorted the same way:
// a particle's candidates are the 5x5x5 cells around its own, all 125 of them (a corner cell's
// nearest point lies w sqrt(3) = 2.4-2.6 from the home cell at the study's edges, within 2.8, so
// none can be dropped), ~335 candidates at 10,976 against ~580. A half cell holds ~2.7 particles,
// so a block takes a group of 2x2x2 home cells (~21 particles), loads their 6x6x6 cells once
// (image-shifted as above, in cell order, x fastest) and each particle goes over its own 25
// stencil rows of 5 cells, each row one contiguous range of the tile; 32 particles a round at L
// lanes each (32 L threads, one round for a group of average size).
//   half-cells-fused-L       cells-fused over the groups' tiles.
//   half-cells-persistent-L  cells-persistent over the groups' tiles.
// Their "list" column is the mean number of candidates per particle; the list check becomes:
// the 27 (125) cells around each particle hold exactly the pairs within rc that the reference finds.
// Forces and positions are compared by original particle id.
// Checks before timing (exit status 1 when one fails): each variant's first forces against an
// all-pairs reference in double; each variant's first list holds exactly the pairs within rc that
// the reference finds; each variant's positions after --check-steps steps against chain's. Then
// a warm-up, and the timed steps with builds per 1000 steps and the total energy drift. A size
// with fewer than 3 list cells per edge (k = 5 and below) is skipped with a message.
//
//   structmd_small_step_variants [--steps S] [--warmup W] [--check-steps C] [--csv PATH]
//                                [--only PREFIX,PREFIX,...] [k ...]
//   (k: fcc cells per edge, 4 k^3 particles; default 10 14 25: 4,000, 10,976 and 62,500;
//   --only: the variants whose names begin with one of the prefixes, e.g. --only half-cells,chain-g;
//   chain always runs, its positions being the trajectory reference; default all)
#include <cooperative_groups.h>
#include <cuda_runtime.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <string>
#include <type_traits>
#include <vector>

#include "core/dependent_launch.hpp"
#include "standalone_cuda.cuh"

namespace cg = cooperative_groups;

namespace {

using standalone::check;

constexpr double kDensity = 0.8442;
constexpr double kTemperature = 1.44;
constexpr float kCutoff = 2.5f;
constexpr float kCutoff2 = kCutoff * kCutoff;
constexpr float kListRadius2 = 2.8f * 2.8f;
constexpr float kHalfSkin2 = 0.15f * 0.15f;
constexpr float kDt = 0.005f;
constexpr float kHalfDt = 0.5f * kDt;
constexpr int kCellCapacity = 64;   // two members a lane in the cell sort; ~18 expected
constexpr int kListCapacity = 128;  // ~78 expected within the list radius
constexpr int kThreads = 256;
constexpr int kStepsPerGraph = 50;  // even: the fused graphs end on the buffer they start from
constexpr int kEngineStepsPerGraph = 16;  // the engine's graph length (chain-g16)

// The device state of one liquid. Positions are double-buffered for the fused and persistent steps.
struct System {
    int n = 0;
    float length = 0;
    int perEdge = 0;  // list cells per edge
    int cells = 0;
    float4* pos[2] = {nullptr, nullptr};
    float4* vel = nullptr;
    float4* force = nullptr;
    float4* posAtBuild = nullptr;
    int* cellCount = nullptr;
    int* cellMember = nullptr;  // kCellCapacity per cell
    int* list = nullptr;        // entry m of particle i at i * particleStride + m * entryStride
    int* listCount = nullptr;
    int particleStride = 0;
    int entryStride = 0;
    int* rebuild = nullptr;        // the displacement flag of chain and fused, cleared by the build
    int* rebuildByStep = nullptr;  // persistent: three flags in rotation (see persistent_steps)
    int* builds = nullptr;
    int* overflow = nullptr;
    unsigned* blocksDone = nullptr;
    unsigned long long* step = nullptr;
    // The cell-tile variants: particles kept sorted by cell, cell c's members at slots
    // cellStart[c] .. cellStart[c + 1] - 1; originalId maps a slot back to the particle; the
    // scratch arrays hold the unsorted state during a build.
    int* cellStart = nullptr;  // cells + 1 entries
    int* originalId = nullptr;
    float4* scratchPos = nullptr;
    float4* scratchVel = nullptr;
    int* scratchId = nullptr;
};

// --- the arithmetic every variant shares -----------------------------------------------------

__device__ __forceinline__ float3 minimum_image(float3 d, float length) {
    d.x -= length * rintf(d.x / length);
    d.y -= length * rintf(d.y / length);
    d.z -= length * rintf(d.z / length);
    return d;
}

__device__ __forceinline__ float3 lj_force(float3 d) {  // on i from j, d = r_i - r_j
    const float r2 = d.x * d.x + d.y * d.y + d.z * d.z;
    if (r2 >= kCutoff2) return {0, 0, 0};
    const float inv2 = 1.f / r2, inv6 = inv2 * inv2 * inv2;
    const float scale = 24.f * inv2 * inv6 * (2.f * inv6 - 1.f);
    return {scale * d.x, scale * d.y, scale * d.z};
}

__device__ __forceinline__ float4 kicked(float4 v, float3 f) {
    v.x += f.x * kHalfDt;
    v.y += f.y * kHalfDt;
    v.z += f.z * kHalfDt;
    return v;
}

__device__ __forceinline__ float wrapped(float x, float length) { return x - length * floorf(x / length); }

__device__ __forceinline__ float4 drifted(float4 x, float4 v, float length) {
    return make_float4(wrapped(x.x + v.x * kDt, length), wrapped(x.y + v.y * kDt, length),
                       wrapped(x.z + v.z * kDt, length), x.w);
}

__device__ __forceinline__ bool moved_past_half_skin(float4 x, float4 atBuild, float length) {
    const float3 d = minimum_image(make_float3(x.x - atBuild.x, x.y - atBuild.y, x.z - atBuild.z), length);
    return d.x * d.x + d.y * d.y + d.z * d.z > kHalfSkin2;
}

__device__ __forceinline__ int cell_coordinate(float x, const System& s) {
    return min(s.perEdge - 1, max(0, static_cast<int>(x / s.length * s.perEdge)));
}

// Loads through the read-only path where the data cannot change during the kernel (chain, fused);
// the persistent kernel writes positions and lists between its barriers, so it loads plainly.
template <bool ReadOnly, class T>
__device__ __forceinline__ T load(const T* p) {
    if constexpr (ReadOnly)
        return __ldg(p);
    else
        return *p;
}

// The L lanes of one particle: a power-of-two segment of a warp.
template <int L>
struct LaneGroup {
    int item;
    int lane;
    unsigned mask;
    __device__ explicit LaneGroup(long long virtualThread)
        : item(static_cast<int>(virtualThread / L)),
          lane(static_cast<int>(virtualThread % L)),
          mask(L == 32 ? 0xffffffffu : ((1u << L) - 1u) << (static_cast<int>(virtualThread % 32) & ~(L - 1))) {}
};

// A force summed by the L lanes of a group, in every lane: a fixed butterfly of shuffles.
template <int L>
__device__ __forceinline__ float3 combined(float3 f, const LaneGroup<L>& g) {
    for (int offset = L / 2; offset > 0; offset /= 2) {
        f.x += __shfl_xor_sync(g.mask, f.x, offset, L);
        f.y += __shfl_xor_sync(g.mask, f.y, offset, L);
        f.z += __shfl_xor_sync(g.mask, f.z, offset, L);
    }
    return f;
}

// The force on particle i, summed over its list by L lanes (lane l takes entries l, l + L, ...),
// combined by a fixed butterfly of shuffles, in every lane.
template <int L, bool ReadOnly>
__device__ __forceinline__ float3 pair_force(const System& s, const float4* pos, const LaneGroup<L>& g) {
    const int i = g.item;
    const float4 p = load<ReadOnly>(pos + i);
    const int m = load<ReadOnly>(s.listCount + i);
    const int* row = s.list + static_cast<long long>(i) * s.particleStride;
    float3 f = {0, 0, 0};
#pragma unroll 2
    for (int k = g.lane; k < m; k += L) {
        const float4 q = load<ReadOnly>(pos + load<ReadOnly>(row + static_cast<long long>(k) * s.entryStride));
        const float3 d = lj_force(minimum_image(make_float3(p.x - q.x, p.y - q.y, p.z - q.z), s.length));
        f.x += d.x;
        f.y += d.y;
        f.z += d.z;
    }
    return combined(f, g);
}

// The fused epilogue of particle i: closing kick of step n (unless this is the first step), opening
// kick of step n+1, drift to x(n+1) in `out`. The same operations, in the same order, as chain's
// kick and drift kernels. Returns whether the particle moved past half the skin since the build.
// Wrap false (cell tiles): the drift leaves the box until the next build wraps it, so that a
// neighbour cell's image shift, fixed at the build, stays right for all its members.
template <bool Wrap = true>
__device__ __forceinline__ bool advance_particle(const System& s, float4 x, float4* out, int i, float3 f, bool closing) {
    float4 v = s.vel[i];
    if (closing) v = kicked(v, f);
    v = kicked(v, f);
    const float4 next =
        Wrap ? drifted(x, v, s.length) : make_float4(x.x + v.x * kDt, x.y + v.y * kDt, x.z + v.z * kDt, x.w);
    out[i] = next;
    s.vel[i] = v;
    return moved_past_half_skin(next, s.posAtBuild[i], s.length);
}

// --- the list build: bin, sort each cell, a warp per particle's list -------------------------

__device__ __forceinline__ void bin_particle(const System& s, const float4* pos, int i) {
    const float4 p = pos[i];
    s.posAtBuild[i] = p;
    const int cell = (cell_coordinate(p.z, s) * s.perEdge + cell_coordinate(p.y, s)) * s.perEdge + cell_coordinate(p.x, s);
    const int slot = atomicAdd(s.cellCount + cell, 1);
    if (slot < kCellCapacity)
        s.cellMember[cell * kCellCapacity + slot] = i;
    else
        atomicAdd(s.overflow, 1);
}

// A warp puts a cell's members in index order (each lane holds two and counts the smaller ones),
// so the lists, and with them the order of every force sum, do not depend on the binning atomics.
__device__ __forceinline__ void sort_cell(const System& s, int cell, int lane) {
    int* members = s.cellMember + cell * kCellCapacity;
    const int count = min(s.cellCount[cell], kCellCapacity);
    const int a = lane < count ? members[lane] : INT_MAX;
    const int b = lane + 32 < count ? members[lane + 32] : INT_MAX;
    int rankA = 0, rankB = 0;
    for (int t = 0; t < 32; ++t) {
        const int otherA = __shfl_sync(0xffffffffu, a, t), otherB = __shfl_sync(0xffffffffu, b, t);
        rankA += (otherA < a) + (otherB < a);
        rankB += (otherA < b) + (otherB < b);
    }
    __syncwarp();
    if (lane < count) members[rankA] = a;
    if (lane + 32 < count) members[rankB] = b;
}

// A warp builds particle i's list: the 27 cells around it in a fixed order, each cell's members
// (in index order) tested by the lanes, the hits written in order through a ballot.
__device__ __forceinline__ void build_list(const System& s, const float4* pos, int i, int lane) {
    const float4 p = pos[i];
    const int cx = cell_coordinate(p.x, s), cy = cell_coordinate(p.y, s), cz = cell_coordinate(p.z, s);
    const int e = s.perEdge;
    int found = 0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int cell = (((cz + dz + e) % e) * e + (cy + dy + e) % e) * e + (cx + dx + e) % e;
                const int count = min(s.cellCount[cell], kCellCapacity);
                for (int base = 0; base < count; base += 32) {
                    const int k = base + lane;
                    const int j = k < count ? s.cellMember[cell * kCellCapacity + k] : -1;
                    bool hit = false;
                    if (j >= 0 && j != i) {
                        const float4 q = pos[j];
                        const float3 d = minimum_image(make_float3(q.x - p.x, q.y - p.y, q.z - p.z), s.length);
                        hit = d.x * d.x + d.y * d.y + d.z * d.z < kListRadius2;
                    }
                    const unsigned hits = __ballot_sync(0xffffffffu, hit);
                    const int entry = found + __popc(hits & ((1u << lane) - 1u));
                    if (hit && entry < kListCapacity)
                        s.list[static_cast<long long>(i) * s.particleStride + static_cast<long long>(entry) * s.entryStride] = j;
                    found += __popc(hits);
                }
            }
    if (lane == 0) {
        s.listCount[i] = min(found, kListCapacity);
        if (found > kListCapacity) atomicAdd(s.overflow, 1);
    }
}

__global__ void clear_cells(System s) {
    structmd::follow_previous_kernel();
    const int c = blockIdx.x * blockDim.x + threadIdx.x;
    if (c < s.cells) s.cellCount[c] = 0;
}

__global__ void bin_particles(System s, const float4* pos) {
    structmd::follow_previous_kernel();
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i == 0) {
        *s.rebuild = 0;
        ++*s.builds;
    }
    if (i < s.n) bin_particle(s, pos, i);
}

__global__ void sort_cells(System s) {
    structmd::follow_previous_kernel();
    const int cell = (blockIdx.x * blockDim.x + threadIdx.x) / 32;
    if (cell < s.cells) sort_cell(s, cell, threadIdx.x % 32);
}

__global__ void build_lists(System s, const float4* pos) {
    structmd::follow_previous_kernel();
    const int i = static_cast<int>((static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x) / 32);
    if (i < s.n) build_list(s, pos, i, threadIdx.x % 32);
}

int blocks_for(long long threads) { return static_cast<int>((threads + kThreads - 1) / kThreads); }

// The build's four kernels on `stream` (issued directly, or captured into an IF node's body).
void launch_build(const System& s, const float4* pos, cudaStream_t stream) {
    clear_cells<<<blocks_for(s.cells), kThreads, 0, stream>>>(s);
    bin_particles<<<blocks_for(s.n), kThreads, 0, stream>>>(s, pos);
    sort_cells<<<blocks_for(32ll * s.cells), kThreads, 0, stream>>>(s);
    build_lists<<<blocks_for(32ll * s.n), kThreads, 0, stream>>>(s, pos);
    check(cudaGetLastError(), "launching the list build");
}

// --- chain: the engine's step, kernel by kernel --------------------------------------------------

__global__ void chain_clock(System s) {
    structmd::follow_previous_kernel();
    ++*s.step;
}

__global__ void chain_drift(System s, float4* pos, float4* vel, int* rebuild) {
    structmd::follow_previous_kernel();
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= s.n) return;
    const float4 f = s.force[i];
    const float4 v = kicked(vel[i], make_float3(f.x, f.y, f.z));
    const float4 next = drifted(pos[i], v, s.length);
    pos[i] = next;
    vel[i] = v;
    if (moved_past_half_skin(next, s.posAtBuild[i], s.length)) *rebuild = 1;
}

__global__ void chain_set_condition(System s, cudaGraphConditionalHandle handle) {
    structmd::follow_previous_kernel();
    cudaGraphSetConditional(handle, *s.rebuild != 0 ? 1u : 0u);
}

template <int L>
__global__ void chain_pair(System s) {
    structmd::follow_previous_kernel();
    const long long t = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
    if (t >= static_cast<long long>(s.n) * L) return;
    const LaneGroup<L> g(t);
    const float3 f = pair_force<L, true>(s, s.pos[0], g);
    if (g.lane == 0) s.force[g.item] = make_float4(f.x, f.y, f.z, 0.f);
}

__global__ void chain_kick(System s) {
    structmd::follow_previous_kernel();
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= s.n) return;
    const float4 f = s.force[i];
    s.vel[i] = kicked(s.vel[i], make_float3(f.x, f.y, f.z));
}

// --- fused: one kernel per step -------------------------------------------------------------------

// Inside a graph (handle set), the last block to finish copies the displacement flag into the IF
// node's condition: one thread sets it, as cudaGraphSetConditional requires, without a setter kernel.
template <int L>
__global__ void fused_step(System s, const float4* __restrict__ in, float4* __restrict__ out, bool closing,
                           cudaGraphConditionalHandle handle, float4* forceOut) {
    const long long t = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
    if (t < static_cast<long long>(s.n) * L) {
        const LaneGroup<L> g(t);
        const float3 f = pair_force<L, true>(s, in, g);
        if (g.lane == 0) {
            if (forceOut) forceOut[g.item] = make_float4(f.x, f.y, f.z, 0.f);
            if (advance_particle(s, __ldg(in + g.item), out, g.item, f, closing)) {
                *s.rebuild = 1;
                __threadfence();  // the flag reaches the last block before this block counts itself done
            }
        }
    }
    if (!handle) return;
    __syncthreads();
    if (threadIdx.x == 0 && atomicAdd(s.blocksDone, 1u) == gridDim.x - 1) {
        *s.blocksDone = 0;
        cudaGraphSetConditional(handle, atomicAdd(s.rebuild, 0) != 0 ? 1u : 0u);
        ++*s.step;
    }
}

// --- persistent: one cooperative launch for many steps ------------------------------------------

// Step g sets rebuildByStep[g % 3]; every block reads it after the barrier that follows; thread 0
// clears rebuildByStep[(g + 2) % 3] then, which every block read in step g - 1 (before this barrier)
// and which step g + 2 sets only after the next barrier, so no clear races with a set or a read.
template <int L>
__global__ void persistent_steps(System s, int parity, long long firstStep, int steps, bool closingFirst,
                                 float4* forceOut) {
    cg::grid_group grid = cg::this_grid();
    const long long threads = static_cast<long long>(gridDim.x) * blockDim.x;
    const long long id = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
    const int lane = threadIdx.x % 32;
    for (int step = 0; step < steps; ++step) {
        const float4* in = s.pos[(parity + step) & 1];
        float4* out = s.pos[(parity + step + 1) & 1];
        const long long g = firstStep + step;
        int* flag = s.rebuildByStep + g % 3;
        // The build of the step before (if any) is over: its cell counts can go.
        for (long long c = id; c < s.cells; c += threads) s.cellCount[c] = 0;
        for (long long t = id; t < static_cast<long long>(s.n) * L; t += threads) {
            const LaneGroup<L> group(t);
            const float3 f = pair_force<L, false>(s, in, group);
            if (group.lane == 0) {
                if (forceOut && step == 0) forceOut[group.item] = make_float4(f.x, f.y, f.z, 0.f);
                if (advance_particle(s, in[group.item], out, group.item, f, closingFirst || step > 0)) *flag = 1;
            }
        }
        grid.sync();
        if (id == 0) {
            s.rebuildByStep[(g + 2) % 3] = 0;
            ++*s.step;
        }
        if (*static_cast<volatile int*>(flag)) {
            if (id == 0) ++*s.builds;
            for (long long i = id; i < s.n; i += threads) bin_particle(s, out, static_cast<int>(i));
            grid.sync();
            for (long long cell = id / 32; cell < s.cells; cell += threads / 32) sort_cell(s, static_cast<int>(cell), lane);
            grid.sync();
            for (long long i = id / 32; i < s.n; i += threads / 32) build_list(s, out, static_cast<int>(i), lane);
            grid.sync();
        }
    }
}

// --- cells: pair forces from cell tiles in shared memory, no list --------------------------------

constexpr int kCellThreads = 128;  // a cell-tile block: kCellThreads / L home members a round
constexpr int kTileCells = 27;     // home cell and its neighbours (3+ cells per edge: distinct)
constexpr int kTileLoadBatch = 8;  // loads in flight per thread while filling a tile
constexpr int kScanThreads = 1024;
// The shared tiles allow 8 blocks a multiprocessor; the fused step needs 72 registers (7 blocks)
// unbounded; the persistent one would take 128 (4 blocks), capped here at 96 (5 blocks).
constexpr int kCellPersistentBlocksPerMultiprocessor = 5;

// The candidates of one home cell: its 27 cells' positions, each shifted by the periodic image
// that puts it beside the home cell (fixed at the build; the drift does not wrap in between).
struct CellTile {
    float4 pos[kTileCells * kCellCapacity];
    int start[kTileCells];
    int offset[kTileCells + 1];  // where each cell's members begin in pos
    float3 shift[kTileCells];
};

// The build, step 1 (thread per particle): wrap the drifted position into the box, copy the
// particle's state to scratch, and bin it.
__device__ __forceinline__ void bin_for_cells(const System& s, const float4* pos, int i) {
    float4 p = pos[i];
    p.x = wrapped(p.x, s.length);
    p.y = wrapped(p.y, s.length);
    p.z = wrapped(p.z, s.length);
    s.scratchPos[i] = p;
    s.scratchVel[i] = s.vel[i];
    s.scratchId[i] = s.originalId[i];
    const int cell =
        (cell_coordinate(p.z, s) * s.perEdge + cell_coordinate(p.y, s)) * s.perEdge + cell_coordinate(p.x, s);
    const int slot = atomicAdd(s.cellCount + cell, 1);
    if (slot < kCellCapacity)
        s.cellMember[cell * kCellCapacity + slot] = i;
    else
        atomicAdd(s.overflow, 1);
}

// Step 2 (one block): cellStart, the exclusive prefix sum of the cells' counts.
__device__ __forceinline__ void scan_cell_counts(const System& s) {
    __shared__ int warpTotals[32];
    const int lane = threadIdx.x % 32, warp = threadIdx.x / 32;
    const int chunk = (s.cells + blockDim.x - 1) / blockDim.x;
    const int first = min(s.cells, static_cast<int>(threadIdx.x) * chunk), last = min(s.cells, first + chunk);
    int sum = 0;
    for (int c = first; c < last; ++c) sum += min(s.cellCount[c], kCellCapacity);
    int inclusive = sum;
    for (int offset = 1; offset < 32; offset *= 2) {
        const int below = __shfl_up_sync(0xffffffffu, inclusive, offset);
        if (lane >= offset) inclusive += below;
    }
    if (lane == 31) warpTotals[warp] = inclusive;
    __syncthreads();
    if (warp == 0) {
        int total = lane < static_cast<int>(blockDim.x / 32) ? warpTotals[lane] : 0;
        for (int offset = 1; offset < 32; offset *= 2) {
            const int below = __shfl_up_sync(0xffffffffu, total, offset);
            if (lane >= offset) total += below;
        }
        warpTotals[lane] = total;
    }
    __syncthreads();
    int start = inclusive - sum + (warp > 0 ? warpTotals[warp - 1] : 0);
    for (int c = first; c < last; ++c) {
        s.cellStart[c] = start;
        start += min(s.cellCount[c], kCellCapacity);
    }
    if (threadIdx.x == blockDim.x - 1) s.cellStart[s.cells] = start;
}

// Step 3 (warp per cell): rank the cell's members by original id (so that the order, and with it
// every force sum, does not depend on the binning atomics) and move each particle's state from
// scratch to its sorted slot.
__device__ __forceinline__ void place_cell(const System& s, float4* pos, int cell, int lane) {
    const int* members = s.cellMember + cell * kCellCapacity;
    const int count = min(s.cellCount[cell], kCellCapacity);
    const int a = lane < count ? members[lane] : -1;
    const int b = lane + 32 < count ? members[lane + 32] : -1;
    const int keyA = a >= 0 ? s.scratchId[a] : INT_MAX, keyB = b >= 0 ? s.scratchId[b] : INT_MAX;
    int rankA = 0, rankB = 0;
    for (int t = 0; t < 32; ++t) {
        const int otherA = __shfl_sync(0xffffffffu, keyA, t), otherB = __shfl_sync(0xffffffffu, keyB, t);
        rankA += (otherA < keyA) + (otherB < keyA);
        rankB += (otherA < keyB) + (otherB < keyB);
    }
    const int base = s.cellStart[cell];
    auto place = [&](int j, int rank) {
        const float4 p = s.scratchPos[j];
        pos[base + rank] = p;
        s.posAtBuild[base + rank] = p;
        s.vel[base + rank] = s.scratchVel[j];
        s.originalId[base + rank] = s.scratchId[j];
    };
    if (a >= 0) place(a, rankA);
    if (b >= 0) place(b, rankB);
}

__global__ void cells_bin(System s, const float4* pos) {
    structmd::follow_previous_kernel();
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i == 0) {
        *s.rebuild = 0;
        ++*s.builds;
    }
    if (i < s.n) bin_for_cells(s, pos, i);
}

__global__ void cells_scan(System s) {
    structmd::follow_previous_kernel();
    scan_cell_counts(s);
}

__global__ void cells_place(System s, float4* pos) {
    structmd::follow_previous_kernel();
    const int cell = (blockIdx.x * blockDim.x + threadIdx.x) / 32;
    if (cell < s.cells) place_cell(s, pos, cell, threadIdx.x % 32);
}

// The re-sort's four kernels on `stream`; the sorted state ends in `pos` (the step's out buffer).
void launch_cells_build(const System& s, float4* pos, cudaStream_t stream) {
    clear_cells<<<blocks_for(s.cells), kThreads, 0, stream>>>(s);
    cells_bin<<<blocks_for(s.n), kThreads, 0, stream>>>(s, pos);
    cells_scan<<<1, kScanThreads, 0, stream>>>(s);
    cells_place<<<blocks_for(32ll * s.cells), kThreads, 0, stream>>>(s, pos);
    check(cudaGetLastError(), "launching the cell re-sort");
}

// Fills the tile of home cell `cell`; returns the number of candidates. Warp 0 finds the 27 cells'
// ranges and image shifts and scans their counts; then every thread loads kTileLoadBatch
// candidates at a time (all in flight before any is stored), each finding its cell by bisection.
template <bool ReadOnly>
__device__ __forceinline__ int load_tile(const System& s, const float4* pos, int cell, CellTile& tile) {
    const int e = s.perEdge;
    __syncthreads();  // the previous tile is no longer read
    if (threadIdx.x < 32) {
        const int lane = threadIdx.x;
        int count = 0;
        if (lane < kTileCells) {
            const int home[3] = {cell % e, (cell / e) % e, cell / (e * e)};
            const int offset[3] = {lane % 3 - 1, (lane / 3) % 3 - 1, lane / 9 - 1};
            int coordinate[3];
            float shift[3];
            for (int a = 0; a < 3; ++a) {
                const int c = home[a] + offset[a];
                shift[a] = c < 0 ? -s.length : (c >= e ? s.length : 0.f);
                coordinate[a] = (c + e) % e;
            }
            const int neighbour = (coordinate[2] * e + coordinate[1]) * e + coordinate[0];
            const int start = load<ReadOnly>(s.cellStart + neighbour);
            count = load<ReadOnly>(s.cellStart + neighbour + 1) - start;
            tile.start[lane] = start;
            tile.shift[lane] = make_float3(shift[0], shift[1], shift[2]);
        }
        int inclusive = count;
        for (int offset = 1; offset < 32; offset *= 2) {
            const int below = __shfl_up_sync(0xffffffffu, inclusive, offset);
            if (lane >= offset) inclusive += below;
        }
        if (lane < kTileCells) tile.offset[lane] = inclusive - count;
        if (lane == kTileCells - 1) tile.offset[kTileCells] = inclusive;
    }
    __syncthreads();
    const int total = tile.offset[kTileCells];
    for (int base = threadIdx.x; base < total; base += kTileLoadBatch * blockDim.x) {
        float4 q[kTileLoadBatch];
        int from[kTileLoadBatch];
#pragma unroll
        for (int b = 0; b < kTileLoadBatch; ++b) {
            const int t = base + b * blockDim.x;
            from[b] = 0;
            for (int step = 16; step > 0; step /= 2)
                if (from[b] + step < kTileCells && tile.offset[from[b] + step] <= t) from[b] += step;
            if (t < total) q[b] = load<ReadOnly>(pos + tile.start[from[b]] + t - tile.offset[from[b]]);
        }
#pragma unroll
        for (int b = 0; b < kTileLoadBatch; ++b) {
            const int t = base + b * blockDim.x;
            if (t >= total) break;
            const float3 shift = tile.shift[from[b]];
            tile.pos[t] = make_float4(q[b].x + shift.x, q[b].y + shift.y, q[b].z + shift.z, q[b].w);
        }
    }
    __syncthreads();
    return total;
}

// Work item `item` (home cell item / parts, part item % parts): the part's home members, L lanes
// each, sum the forces of the tile's candidates within rc (lane l takes l, l + L, ...; the member
// itself skipped by its tile index), combine them by shuffles, and take the fused epilogue.
template <int L, bool ReadOnly>
__device__ __forceinline__ void cells_pair_item(const System& s, const float4* in, float4* out, int item, int parts,
                                                bool closing, float4* forceOut, int* flag, CellTile& tile) {
    const int cell = item / parts, part = item % parts;
    const int total = load_tile<ReadOnly>(s, in, cell, tile);
    const int homeOffset = tile.offset[kTileCells / 2], homeStart = tile.start[kTileCells / 2];
    const int members = tile.offset[kTileCells / 2 + 1] - homeOffset;
    constexpr int kMembersPerRound = kCellThreads / L;
    const LaneGroup<L> g(threadIdx.x);
    for (int round = part; round * kMembersPerRound < members; round += parts) {
        const int m = round * kMembersPerRound + g.item;
        if (m >= members) continue;
        const int self = homeOffset + m;
        const float4 p = tile.pos[self];
        float3 f = {0, 0, 0};
#pragma unroll 4
        for (int c = g.lane; c < total; c += L) {
            const float4 q = tile.pos[c];
            const float3 d = make_float3(p.x - q.x, p.y - q.y, p.z - q.z);
            if (c != self) {
                const float3 pair = lj_force(d);
                f.x += pair.x;
                f.y += pair.y;
                f.z += pair.z;
            }
        }
        f = combined(f, g);
        if (g.lane == 0) {
            const int i = homeStart + m;
            if (forceOut) forceOut[s.originalId[i]] = make_float4(f.x, f.y, f.z, 0.f);
            if (advance_particle<false>(s, p, out, i, f, closing)) {
                *flag = 1;
                __threadfence();  // the flag reaches the last block before this block counts itself done
            }
        }
    }
}

// fused over cell tiles: a block per (home cell, part); the last block sets the IF node's condition
// as fused_step does.
template <int L>
__global__ void __launch_bounds__(kCellThreads)
    cells_fused_step(System s, const float4* __restrict__ in, float4* __restrict__ out, int parts, bool closing,
                     cudaGraphConditionalHandle handle, float4* forceOut) {
    __shared__ CellTile tile;
    cells_pair_item<L, true>(s, in, out, blockIdx.x, parts, closing, forceOut, s.rebuild, tile);
    if (!handle) return;
    __syncthreads();
    if (threadIdx.x == 0 && atomicAdd(s.blocksDone, 1u) == gridDim.x - 1) {
        *s.blocksDone = 0;
        cudaGraphSetConditional(handle, atomicAdd(s.rebuild, 0) != 0 ? 1u : 0u);
        ++*s.step;
    }
}

// persistent over cell tiles: the blocks take the (cell, part) items in turn, then the flag logic
// of persistent_steps, with the re-sort's three phases in place of the list build's.
template <int L>
__global__ void __launch_bounds__(kCellThreads, kCellPersistentBlocksPerMultiprocessor)
    cells_persistent_steps(System s, int parity, long long firstStep, int steps, int parts, bool closingFirst,
                           float4* forceOut) {
    __shared__ CellTile tile;
    cg::grid_group grid = cg::this_grid();
    const long long threads = static_cast<long long>(gridDim.x) * blockDim.x;
    const long long id = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
    const int lane = threadIdx.x % 32;
    const int items = s.cells * parts;
    for (int step = 0; step < steps; ++step) {
        const float4* in = s.pos[(parity + step) & 1];
        float4* out = s.pos[(parity + step + 1) & 1];
        const long long g = firstStep + step;
        int* flag = s.rebuildByStep + g % 3;
        for (long long c = id; c < s.cells; c += threads) s.cellCount[c] = 0;
        for (int item = blockIdx.x; item < items; item += gridDim.x)
            cells_pair_item<L, false>(s, in, out, item, parts, closingFirst || step > 0, step == 0 ? forceOut : nullptr,
                                      flag, tile);
        grid.sync();
        if (id == 0) {
            s.rebuildByStep[(g + 2) % 3] = 0;
            ++*s.step;
        }
        if (*static_cast<volatile int*>(flag)) {
            if (id == 0) ++*s.builds;
            for (long long i = id; i < s.n; i += threads) bin_for_cells(s, out, static_cast<int>(i));
            grid.sync();
            if (blockIdx.x == 0) scan_cell_counts(s);
            grid.sync();
            for (long long cell = id / 32; cell < s.cells; cell += threads / 32)
                place_cell(s, out, static_cast<int>(cell), lane);
            grid.sync();
        }
    }
}

// --- half cells: cells of half the edge, 2x2x2 home cells a block ------------------------------

// Cells of edge >= 1.4 (half the list radius), so a particle's candidates are the 5x5x5 cells
// around its own: all 125 are needed, since even a corner cell's nearest point lies w sqrt(3)
// (2.4-2.6 at the edges the study's boxes give) from the home cell, within 2.8. A half cell holds
// ~2.7 particles, too few to fill a block, so a block takes a group of 2x2x2 home cells (~21
// particles) and loads their shared 6x6x6 neighbourhood once: 27 loads a home particle against the
// 27 cells' ~27 (a cell of the full edge, ~21 particles, loads as many), while each particle tests
// only its own 5x5x5 window of the tile (~335 candidates at 10,976 instead of ~580). A row of home
// cells instead would load 8x5x5 cells for ~11 particles. The block has kHalfMembersPerRound
// particles of L lanes each, one round for a group of average size.
constexpr int kHalfGroupEdge = 2;
constexpr int kHalfReach = 2;  // stencil cells on each side of the home cell
constexpr int kHalfStencilEdge = 2 * kHalfReach + 1;
constexpr int kHalfTileEdge = kHalfGroupEdge + 2 * kHalfReach;
constexpr int kHalfTileCells = kHalfTileEdge * kHalfTileEdge * kHalfTileEdge;
constexpr int kHalfHomeCells = kHalfGroupEdge * kHalfGroupEdge * kHalfGroupEdge;
constexpr int kHalfTileCapacity = 1024;  // ~580-650 expected at the study's sizes; more counts as overflow
constexpr int kHalfMembersPerRound = 32;
constexpr float kHalfCellEdge = 1.4f;
// The persistent kernel takes 114-116 registers unbounded; 16 warps a multiprocessor (128 registers:
// 8, 4, 2 blocks at L = 2, 4, 8) keeps it unspilled and all 512 groups of 10,976 resident at L <= 4,
// where 24 (80 registers) spills ~150 bytes a thread.
constexpr int kHalfPersistentWarpsPerMultiprocessor = 16;

__host__ __device__ constexpr int half_cell_groups_per_edge(int perEdge) {
    return (perEdge + kHalfGroupEdge - 1) / kHalfGroupEdge;
}

// The tile of one group: the 6x6x6 cells' image-shifted positions in cell order (x fastest, so
// that a stencil row of 5 cells is one contiguous range) and where each cell begins.
struct HalfCellTile {
    float4 pos[kHalfTileCapacity];
    int start[kHalfTileCells];
    int offset[kHalfTileCells + 1];
    float shift[3][kHalfTileEdge];
    int homeOffset[kHalfHomeCells + 1];  // the home members' numbering, home cell by home cell
};

// Fills the tile of group `group`; returns the number of home members. Home cells beyond the box
// (the last group along an axis when the cells per edge are odd) have none.
template <bool ReadOnly>
__device__ __forceinline__ int load_half_tile(const System& s, const float4* pos, int group, HalfCellTile& tile) {
    const int e = s.perEdge, groupsPerEdge = half_cell_groups_per_edge(e);
    const int first[3] = {group % groupsPerEdge * kHalfGroupEdge - kHalfReach,
                          (group / groupsPerEdge) % groupsPerEdge * kHalfGroupEdge - kHalfReach,
                          group / (groupsPerEdge * groupsPerEdge) * kHalfGroupEdge - kHalfReach};
    __syncthreads();  // the previous tile is no longer read
    for (int t = threadIdx.x; t < kHalfTileCells; t += blockDim.x) {
        const int local[3] = {t % kHalfTileEdge, (t / kHalfTileEdge) % kHalfTileEdge,
                              t / (kHalfTileEdge * kHalfTileEdge)};
        int coordinate[3];
        for (int a = 0; a < 3; ++a) coordinate[a] = (first[a] + local[a] + e) % e;
        const int neighbour = (coordinate[2] * e + coordinate[1]) * e + coordinate[0];
        const int start = load<ReadOnly>(s.cellStart + neighbour);
        tile.start[t] = start;
        tile.offset[t] = load<ReadOnly>(s.cellStart + neighbour + 1) - start;  // the count, scanned below
    }
    if (threadIdx.x < 3 * kHalfTileEdge) {
        const int axis = threadIdx.x / kHalfTileEdge, local = threadIdx.x % kHalfTileEdge;
        const int c = (axis == 0 ? first[0] : axis == 1 ? first[1] : first[2]) + local;  // no local-memory array
        tile.shift[axis][local] = c < 0 ? -s.length : (c >= e ? s.length : 0.f);
    }
    __syncthreads();
    if (threadIdx.x < 32) {
        constexpr int kCellsPerLane = (kHalfTileCells + 31) / 32;
        const int lane = threadIdx.x, begin = lane * kCellsPerLane;
        int count[kCellsPerLane], sum = 0;
#pragma unroll
        for (int k = 0; k < kCellsPerLane; ++k) {
            count[k] = begin + k < kHalfTileCells ? tile.offset[begin + k] : 0;
            sum += count[k];
        }
        int inclusive = sum;
        for (int offset = 1; offset < 32; offset *= 2) {
            const int below = __shfl_up_sync(0xffffffffu, inclusive, offset);
            if (lane >= offset) inclusive += below;
        }
        // Clamped to the capacity so that an overflow (counted, failing the run) stays in bounds.
        int running = inclusive - sum;
#pragma unroll
        for (int k = 0; k < kCellsPerLane; ++k) {
            if (begin + k < kHalfTileCells) tile.offset[begin + k] = min(running, kHalfTileCapacity);
            running += count[k];
        }
        if (lane == 31) {
            tile.offset[kHalfTileCells] = min(running, kHalfTileCapacity);
            if (running > kHalfTileCapacity) atomicAdd(s.overflow, 1);
        }
    }
    __syncthreads();
    if (threadIdx.x <= kHalfHomeCells) {
        int members = 0;
        for (int h = 0; h < static_cast<int>(threadIdx.x); ++h) {
            const int local[3] = {h % kHalfGroupEdge, (h / kHalfGroupEdge) % kHalfGroupEdge,
                                  h / (kHalfGroupEdge * kHalfGroupEdge)};
            bool inBox = true;
            for (int a = 0; a < 3; ++a) inBox = inBox && first[a] + kHalfReach + local[a] < e;
            const int cell = ((local[2] + kHalfReach) * kHalfTileEdge + local[1] + kHalfReach) * kHalfTileEdge +
                             local[0] + kHalfReach;
            if (inBox) members += tile.offset[cell + 1] - tile.offset[cell];
        }
        tile.homeOffset[threadIdx.x] = members;
    }
    const int total = tile.offset[kHalfTileCells];
    for (int base = threadIdx.x; base < total; base += kTileLoadBatch * blockDim.x) {
        float4 q[kTileLoadBatch];
        int from[kTileLoadBatch];
#pragma unroll
        for (int b = 0; b < kTileLoadBatch; ++b) {
            const int t = base + b * blockDim.x;
            from[b] = 0;
            for (int step = 128; step > 0; step /= 2)
                if (from[b] + step < kHalfTileCells && tile.offset[from[b] + step] <= t) from[b] += step;
            if (t < total) q[b] = load<ReadOnly>(pos + tile.start[from[b]] + t - tile.offset[from[b]]);
        }
#pragma unroll
        for (int b = 0; b < kTileLoadBatch; ++b) {
            const int t = base + b * blockDim.x;
            if (t >= total) break;
            const int cell = from[b];
            const float3 shift = make_float3(tile.shift[0][cell % kHalfTileEdge],
                                             tile.shift[1][(cell / kHalfTileEdge) % kHalfTileEdge],
                                             tile.shift[2][cell / (kHalfTileEdge * kHalfTileEdge)]);
            tile.pos[t] = make_float4(q[b].x + shift.x, q[b].y + shift.y, q[b].z + shift.z, q[b].w);
        }
    }
    __syncthreads();
    return tile.homeOffset[kHalfHomeCells];
}

// Work item `item` (group item / parts, part item % parts): the part's home members, L lanes each,
// go over their 25 stencil rows (5 cells, contiguous in the tile; lane l takes l, l + L, ... of
// each row), keep the candidates within rc, combine by shuffles and take the fused epilogue.
template <int L, bool ReadOnly>
__device__ __forceinline__ void half_cells_pair_item(const System& s, const float4* in, float4* out, int item,
                                                     int parts, bool closing, float4* forceOut, int* flag,
                                                     HalfCellTile& tile) {
    const int group = item / parts, part = item % parts;
    const int members = load_half_tile<ReadOnly>(s, in, group, tile);
    const LaneGroup<L> g(threadIdx.x);
    for (int round = part; round * kHalfMembersPerRound < members; round += parts) {
        const int m = round * kHalfMembersPerRound + g.item;
        if (m >= members) continue;
        int home = 0;
        while (tile.homeOffset[home + 1] <= m) ++home;
        const int hx = home % kHalfGroupEdge, hy = (home / kHalfGroupEdge) % kHalfGroupEdge,
                  hz = home / (kHalfGroupEdge * kHalfGroupEdge);
        const int homeCell = ((hz + kHalfReach) * kHalfTileEdge + hy + kHalfReach) * kHalfTileEdge + hx + kHalfReach;
        const int rank = m - tile.homeOffset[home];
        const int self = tile.offset[homeCell] + rank;
        if (self >= kHalfTileCapacity) continue;  // an overflowed tile (counted): stay in bounds
        const float4 p = tile.pos[self];
        float3 f = {0, 0, 0};
        for (int dz = 0; dz < kHalfStencilEdge; ++dz)
            for (int dy = 0; dy < kHalfStencilEdge; ++dy) {
                const int row = ((hz + dz) * kHalfTileEdge + hy + dy) * kHalfTileEdge + hx;
                const int end = tile.offset[row + kHalfStencilEdge];
#pragma unroll 2
                for (int c = tile.offset[row] + g.lane; c < end; c += L) {
                    const float4 q = tile.pos[c];
                    const float3 d = make_float3(p.x - q.x, p.y - q.y, p.z - q.z);
                    if (c != self) {
                        const float3 pair = lj_force(d);
                        f.x += pair.x;
                        f.y += pair.y;
                        f.z += pair.z;
                    }
                }
            }
        f = combined(f, g);
        if (g.lane == 0) {
            const int i = tile.start[homeCell] + rank;
            if (forceOut) forceOut[s.originalId[i]] = make_float4(f.x, f.y, f.z, 0.f);
            if (advance_particle<false>(s, p, out, i, f, closing)) {
                *flag = 1;
                __threadfence();  // the flag reaches the last block before this block counts itself done
            }
        }
    }
}

// fused over half cells: a block per (group, part); the last block sets the IF node's condition
// as fused_step does.
template <int L>
__global__ void __launch_bounds__(kHalfMembersPerRound* L)
    half_cells_fused_step(System s, const float4* __restrict__ in, float4* __restrict__ out, int parts, bool closing,
                          cudaGraphConditionalHandle handle, float4* forceOut) {
    __shared__ HalfCellTile tile;
    half_cells_pair_item<L, true>(s, in, out, blockIdx.x, parts, closing, forceOut, s.rebuild, tile);
    if (!handle) return;
    __syncthreads();
    if (threadIdx.x == 0 && atomicAdd(s.blocksDone, 1u) == gridDim.x - 1) {
        *s.blocksDone = 0;
        cudaGraphSetConditional(handle, atomicAdd(s.rebuild, 0) != 0 ? 1u : 0u);
        ++*s.step;
    }
}

// persistent over half cells: cells_persistent_steps with the groups' tiles.
template <int L>
__global__ void __launch_bounds__(kHalfMembersPerRound* L, kHalfPersistentWarpsPerMultiprocessor / L)
    half_cells_persistent_steps(System s, int parity, long long firstStep, int steps, int parts, bool closingFirst,
                                float4* forceOut) {
    __shared__ HalfCellTile tile;
    cg::grid_group grid = cg::this_grid();
    const long long threads = static_cast<long long>(gridDim.x) * blockDim.x;
    const long long id = static_cast<long long>(blockIdx.x) * blockDim.x + threadIdx.x;
    const int lane = threadIdx.x % 32;
    const int groupsPerEdge = half_cell_groups_per_edge(s.perEdge);
    const int items = groupsPerEdge * groupsPerEdge * groupsPerEdge * parts;
    for (int step = 0; step < steps; ++step) {
        const float4* in = s.pos[(parity + step) & 1];
        float4* out = s.pos[(parity + step + 1) & 1];
        const long long g = firstStep + step;
        int* flag = s.rebuildByStep + g % 3;
        for (long long c = id; c < s.cells; c += threads) s.cellCount[c] = 0;
        for (int item = blockIdx.x; item < items; item += gridDim.x)
            half_cells_pair_item<L, false>(s, in, out, item, parts, closingFirst || step > 0,
                                           step == 0 ? forceOut : nullptr, flag, tile);
        grid.sync();
        if (id == 0) {
            s.rebuildByStep[(g + 2) % 3] = 0;
            ++*s.step;
        }
        if (*static_cast<volatile int*>(flag)) {
            if (id == 0) ++*s.builds;
            for (long long i = id; i < s.n; i += threads) bin_for_cells(s, out, static_cast<int>(i));
            grid.sync();
            if (blockIdx.x == 0) scan_cell_counts(s);
            grid.sync();
            for (long long cell = id / 32; cell < s.cells; cell += threads / 32)
                place_cell(s, out, static_cast<int>(cell), lane);
            grid.sync();
        }
    }
}

// --- the reference and the checks (double precision, all pairs) ---------------------------------

__device__ double3 minimum_image_double(float4 p, float4 q, double length) {
    double3 d = {double(p.x) - double(q.x), double(p.y) - double(q.y), double(p.z) - double(q.z)};
    d.x -= length * rint(d.x / length);
    d.y -= length * rint(d.y / length);
    d.z -= length * rint(d.z / length);
    return d;
}

// Per particle: the force, half its pair energies (shifted to zero at rc, so that the energy is
// continuous where the truncated force is), the sum of the pair forces' magnitudes (the scale of
// the round-off) and the number of pairs within rc.
__global__ void reference_forces(int n, const float4* pos, double length, double3* force, double* energy,
                                 double* magnitudes, int* withinCutoff) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    const float4 p = pos[i];
    const double rc2 = double(kCutoff) * kCutoff, rc6 = rc2 * rc2 * rc2;
    const double shift = 4.0 * (1.0 / (rc6 * rc6) - 1.0 / rc6);
    double3 f = {0, 0, 0};
    double e = 0, sum = 0;
    int count = 0;
    for (int j = 0; j < n; ++j) {
        if (j == i) continue;
        const double3 d = minimum_image_double(p, pos[j], length);
        const double r2 = d.x * d.x + d.y * d.y + d.z * d.z;
        if (r2 >= rc2) continue;
        const double inv2 = 1.0 / r2, inv6 = inv2 * inv2 * inv2;
        const double scale = 24.0 * inv2 * inv6 * (2.0 * inv6 - 1.0);
        f.x += scale * d.x;
        f.y += scale * d.y;
        f.z += scale * d.z;
        e += 0.5 * (4.0 * inv6 * (inv6 - 1.0) - shift);
        sum += fabs(scale) * sqrt(r2);
        ++count;
    }
    force[i] = f;
    energy[i] = e;
    magnitudes[i] = sum;
    withinCutoff[i] = count;
}

// How many of particle i's list entries lie within rc, by the reference's arithmetic.
__global__ void listed_within_cutoff(System s, const float4* pos, int* withinCutoff) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= s.n) return;
    const double rc2 = double(kCutoff) * kCutoff;
    int count = 0;
    for (int m = 0; m < s.listCount[i]; ++m) {
        const int j = s.list[static_cast<long long>(i) * s.particleStride + static_cast<long long>(m) * s.entryStride];
        const double3 d = minimum_image_double(pos[i], pos[j], s.length);
        count += d.x * d.x + d.y * d.y + d.z * d.z < rc2;
    }
    withinCutoff[i] = count;
}

// The cell tiles' counterpart: how many of the candidates in the cells around sorted particle i
// (`reach` cells on each side: the 27 cells, or the half cells' 125) lie within rc, stored at its
// original id.
__global__ void candidates_within_cutoff(System s, const float4* pos, int* withinCutoff, int reach) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= s.n) return;
    const double rc2 = double(kCutoff) * kCutoff;
    const int e = s.perEdge;
    int cell = 0;
    while (s.cellStart[cell + 1] <= i) ++cell;
    const int cx = cell % e, cy = (cell / e) % e, cz = cell / (e * e);
    int count = 0;
    for (int dz = -reach; dz <= reach; ++dz)
        for (int dy = -reach; dy <= reach; ++dy)
            for (int dx = -reach; dx <= reach; ++dx) {
                const int neighbour = (((cz + dz + e) % e) * e + (cy + dy + e) % e) * e + (cx + dx + e) % e;
                for (int j = s.cellStart[neighbour]; j < s.cellStart[neighbour + 1]; ++j) {
                    if (j == i) continue;
                    const double3 d = minimum_image_double(pos[i], pos[j], s.length);
                    count += d.x * d.x + d.y * d.y + d.z * d.z < rc2;
                }
            }
    withinCutoff[s.originalId[i]] = count;
}

// --- host side --------------------------------------------------------------------------------------

template <class T>
T* device_array(size_t count) {
    T* d = nullptr;
    check(cudaMalloc(&d, std::max<size_t>(1, count) * sizeof(T)), "cudaMalloc");
    check(cudaMemset(d, 0, std::max<size_t>(1, count) * sizeof(T)), "cudaMemset");
    return d;
}

template <class T>
std::vector<T> to_host(const T* d, size_t count) {
    std::vector<T> h(count);
    check(cudaMemcpy(h.data(), d, count * sizeof(T), cudaMemcpyDeviceToHost), "copy to host");
    return h;
}

template <class T>
T read_one(const T* d) {
    return to_host(d, 1)[0];
}

struct Liquid {
    float length = 0;
    int perEdge = 0;
    std::vector<float4> pos, vel;
};

// fcc at the benchmark's density, jittered, sorted by list cell (so that neighbours are near in
// memory), velocities from a Gaussian at kTemperature with the total momentum removed.
Liquid make_liquid(int cellsPerEdge) {
    Liquid liquid;
    const double a = std::cbrt(4.0 / kDensity);
    liquid.length = static_cast<float>(a * cellsPerEdge);
    liquid.perEdge = static_cast<int>(std::floor(liquid.length / std::sqrt(kListRadius2)));
    uint64_t state = 12345;
    auto uniform = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return (static_cast<double>(state >> 11) + 0.5) / 9007199254740992.0;
    };
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    auto wrap = [&](double v) {
        const float w = static_cast<float>(std::fmod(v + 10 * liquid.length, liquid.length));
        return w < liquid.length ? w : 0.f;
    };
    for (int x = 0; x < cellsPerEdge; ++x)
        for (int y = 0; y < cellsPerEdge; ++y)
            for (int z = 0; z < cellsPerEdge; ++z)
                for (const auto& b : basis)
                    liquid.pos.push_back({wrap((x + b[0]) * a + 0.1 * (uniform() - 0.5)),
                                          wrap((y + b[1]) * a + 0.1 * (uniform() - 0.5)),
                                          wrap((z + b[2]) * a + 0.1 * (uniform() - 0.5)), 0.f});
    const int e = liquid.perEdge;
    auto cell_of = [&](const float4& p) {
        auto c = [&](float v) { return std::min(e - 1, static_cast<int>(v / liquid.length * e)); };
        return (c(p.z) * e + c(p.y)) * e + c(p.x);
    };
    std::stable_sort(liquid.pos.begin(), liquid.pos.end(),
                     [&](const float4& p, const float4& q) { return cell_of(p) < cell_of(q); });
    const size_t n = liquid.pos.size();
    std::vector<double> v(3 * n);
    for (size_t k = 0; k < 3 * n; k += 2) {
        const double r = std::sqrt(-2.0 * std::log(uniform())), phi = 2.0 * M_PI * uniform();
        v[k] = r * std::cos(phi);
        if (k + 1 < 3 * n) v[k + 1] = r * std::sin(phi);
    }
    double mean[3] = {0, 0, 0}, sum2 = 0;
    for (size_t i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d) mean[d] += v[3 * i + d] / n;
    for (size_t i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d) sum2 += (v[3 * i + d] - mean[d]) * (v[3 * i + d] - mean[d]);
    const double scale = std::sqrt(3.0 * (n - 1) * kTemperature / sum2);
    for (size_t i = 0; i < n; ++i)
        liquid.vel.push_back({static_cast<float>((v[3 * i] - mean[0]) * scale),
                              static_cast<float>((v[3 * i + 1] - mean[1]) * scale),
                              static_cast<float>((v[3 * i + 2] - mean[2]) * scale), 0.f});
    return liquid;
}

struct Reference {
    std::vector<double3> force;
    std::vector<double> energy, magnitudes;
    std::vector<int> withinCutoff;
};

Reference reference_at(const System& s, const float4* pos) {
    double3* force = device_array<double3>(s.n);
    double *energy = device_array<double>(s.n), *magnitudes = device_array<double>(s.n);
    int* within = device_array<int>(s.n);
    reference_forces<<<blocks_for(s.n), kThreads>>>(s.n, pos, s.length, force, energy, magnitudes, within);
    check(cudaDeviceSynchronize(), "reference forces");
    Reference r{to_host(force, s.n), to_host(energy, s.n), to_host(magnitudes, s.n), to_host(within, s.n)};
    cudaFree(force);
    cudaFree(energy);
    cudaFree(magnitudes);
    cudaFree(within);
    return r;
}

// Total energy; `halfStep`: the velocities are v(n - 1/2) at x(n) (fused, persistent), completed
// here with the reference force's half kick.
double total_energy(const System& s, const float4* pos, bool halfStep) {
    const Reference r = reference_at(s, pos);
    const std::vector<float4> vel = to_host(s.vel, s.n);
    double e = 0;
    for (int i = 0; i < s.n; ++i) {
        double v[3] = {vel[i].x, vel[i].y, vel[i].z};
        if (halfStep) {
            v[0] += r.force[i].x * kHalfDt;
            v[1] += r.force[i].y * kHalfDt;
            v[2] += r.force[i].z * kHalfDt;
        }
        e += 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + r.energy[i];
    }
    return e;
}

// `perEdge`: the cells per edge of the binning (the list cells' by default; the half cells' need
// a system of their own).
System make_system(const Liquid& liquid, int perEdge) {
    System s;
    s.n = static_cast<int>(liquid.pos.size());
    s.length = liquid.length;
    s.perEdge = perEdge;
    s.cells = s.perEdge * s.perEdge * s.perEdge;
    for (float4*& p : s.pos) p = device_array<float4>(s.n);
    s.vel = device_array<float4>(s.n);
    s.force = device_array<float4>(s.n);
    s.posAtBuild = device_array<float4>(s.n);
    s.cellCount = device_array<int>(s.cells);
    s.cellMember = device_array<int>(static_cast<size_t>(s.cells) * kCellCapacity);
    s.list = device_array<int>(static_cast<size_t>(s.n) * kListCapacity);
    s.listCount = device_array<int>(s.n);
    s.rebuild = device_array<int>(1);
    s.rebuildByStep = device_array<int>(3);
    s.builds = device_array<int>(1);
    s.overflow = device_array<int>(1);
    s.blocksDone = device_array<unsigned>(1);
    s.step = device_array<unsigned long long>(1);
    s.cellStart = device_array<int>(s.cells + 1);
    s.originalId = device_array<int>(s.n);
    s.scratchPos = device_array<float4>(s.n);
    s.scratchVel = device_array<float4>(s.n);
    s.scratchId = device_array<int>(s.n);
    return s;
}

void free_system(System& s) {
    for (void* p :
         {static_cast<void*>(s.pos[0]),     static_cast<void*>(s.pos[1]),        static_cast<void*>(s.vel),
          static_cast<void*>(s.force),      static_cast<void*>(s.posAtBuild),    static_cast<void*>(s.cellCount),
          static_cast<void*>(s.cellMember), static_cast<void*>(s.list),          static_cast<void*>(s.listCount),
          static_cast<void*>(s.rebuild),    static_cast<void*>(s.rebuildByStep), static_cast<void*>(s.builds),
          static_cast<void*>(s.overflow),   static_cast<void*>(s.blocksDone),    static_cast<void*>(s.step),
          static_cast<void*>(s.cellStart),  static_cast<void*>(s.originalId),    static_cast<void*>(s.scratchPos),
          static_cast<void*>(s.scratchVel), static_cast<void*>(s.scratchId)})
        cudaFree(p);
}

enum class Design { kChain, kFused, kPersistent, kCellsFused, kCellsPersistent, kHalfCellsFused, kHalfCellsPersistent };

bool over_half_cells(Design design) {
    return design == Design::kHalfCellsFused || design == Design::kHalfCellsPersistent;
}
bool over_cells(Design design) {
    return design == Design::kCellsFused || design == Design::kCellsPersistent || over_half_cells(design);
}
bool persistent(Design design) {
    return design == Design::kPersistent || design == Design::kCellsPersistent ||
           design == Design::kHalfCellsPersistent;
}

std::string variant_name(Design design, int lanes, int stepsPerGraph) {
    const std::string l = std::to_string(lanes);
    switch (design) {
        case Design::kChain: return stepsPerGraph == kStepsPerGraph ? "chain" : "chain-g" + std::to_string(stepsPerGraph);
        case Design::kFused: return "fused-" + l;
        case Design::kPersistent: return "persistent-" + l;
        case Design::kCellsFused: return "cells-fused-" + l;
        case Design::kCellsPersistent: return "cells-persistent-" + l;
        case Design::kHalfCellsFused: return "half-cells-fused-" + l;
        default: return "half-cells-persistent-" + l;
    }
}

template <class F>
void with_lanes(int lanes, F&& f) {
    switch (lanes) {
        case 1: f(std::integral_constant<int, 1>{}); break;
        case 2: f(std::integral_constant<int, 2>{}); break;
        case 4: f(std::integral_constant<int, 4>{}); break;
        case 8: f(std::integral_constant<int, 8>{}); break;
        case 16: f(std::integral_constant<int, 16>{}); break;
        default: f(std::integral_constant<int, 32>{}); break;
    }
}

// A launch captured with a programmatic edge from the kernel before it when `programmatic`.
template <class... Params, class... Args>
void launch(void (*kernel)(Params...), int blocks, int threads, cudaStream_t stream, bool programmatic, Args... args) {
    cudaLaunchConfig_t config{};
    config.gridDim = dim3(blocks);
    config.blockDim = dim3(threads);
    config.stream = stream;
    cudaLaunchAttribute attribute{};
    attribute.id = cudaLaunchAttributeProgrammaticStreamSerialization;
    attribute.val.programmaticStreamSerializationAllowed = 1;
    config.attrs = programmatic ? &attribute : nullptr;
    config.numAttrs = programmatic ? 1 : 0;
    check(cudaLaunchKernelEx(&config, kernel, args...), "launching a kernel");
}

cudaGraph_t capturing_graph(cudaStream_t stream) {
    cudaStreamCaptureStatus status{};
    cudaGraph_t graph = nullptr;
    check(cudaStreamGetCaptureInfo(stream, &status, nullptr, &graph), "capture info");
    return graph;
}

// Appends to the capture on `stream` an IF node on `handle` whose body is what `body` launches on
// `bodyStream`. The edge into the node is a plain one.
template <class Body>
void capture_if(cudaStream_t stream, cudaStream_t bodyStream, cudaGraphConditionalHandle handle, Body&& body) {
    cudaStreamCaptureStatus status{};
    cudaGraph_t graph = nullptr;
    const cudaGraphNode_t* dependencies = nullptr;
    const cudaGraphEdgeData* edges = nullptr;
    size_t count = 0;
    check(cudaStreamGetCaptureInfo(stream, &status, nullptr, &graph, &dependencies, &edges, &count), "capture info");
    cudaGraphNodeParams params{};
    params.type = cudaGraphNodeTypeConditional;
    params.conditional.handle = handle;
    params.conditional.type = cudaGraphCondTypeIf;
    params.conditional.size = 1;
    cudaGraphNode_t node = nullptr;
    check(cudaGraphAddNode(&node, graph, dependencies, nullptr, count, &params), "adding an IF node");
    check(cudaStreamUpdateCaptureDependencies(stream, &node, nullptr, 1, cudaStreamSetCaptureDependencies),
          "capture dependencies");
    cudaGraph_t bodyGraph = params.conditional.phGraph_out[0];
    check(cudaStreamBeginCaptureToGraph(bodyStream, bodyGraph, nullptr, nullptr, 0, cudaStreamCaptureModeRelaxed),
          "capturing an IF body");
    body(bodyStream);
    check(cudaStreamEndCapture(bodyStream, &bodyGraph), "capturing an IF body");
}

// One variant on one liquid: its state, its graph or cooperative grid, and its steps.
// `stepsPerGraph`: kStepsPerGraph but for chain-g16; a run that is not a multiple of it ends on a
// shorter graph (chain only: the fused graphs keep an even length for their buffers' parity).
class Variant {
public:
    Variant(Design design, int lanes, int stepsPerGraph, System& s, cudaStream_t stream, cudaStream_t bodyStream)
        : design_(design),
          lanes_(lanes),
          stepsPerGraph_(stepsPerGraph),
          s_(s),
          stream_(stream),
          bodyStream_(bodyStream) {}
    Variant(const Variant&) = delete;
    Variant& operator=(const Variant&) = delete;
    ~Variant() {
        if (exec_) cudaGraphExecDestroy(exec_);
        if (remainderExec_) cudaGraphExecDestroy(remainderExec_);
    }

    std::string name() const { return variant_name(design_, lanes_, stepsPerGraph_); }
    int grid() const {
        if (persistent(design_)) return cooperativeBlocks_;
        return over_cells(design_) ? tile_items() : blocks_for(static_cast<long long>(s_.n) * lanes_);
    }

    // Puts the liquid in the state at step 0 with its list built, and lays the list out for the
    // variant's lanes (by columns for one lane per particle, by rows for several, as the engine).
    void reset(const Liquid& liquid) {
        check(cudaMemcpy(s_.pos[0], liquid.pos.data(), sizeof(float4) * s_.n, cudaMemcpyHostToDevice), "copy");
        check(cudaMemcpy(s_.vel, liquid.vel.data(), sizeof(float4) * s_.n, cudaMemcpyHostToDevice), "copy");
        for (int* counter : {s_.rebuild, s_.builds, s_.overflow}) check(cudaMemset(counter, 0, sizeof(int)), "memset");
        check(cudaMemset(s_.rebuildByStep, 0, 3 * sizeof(int)), "memset");
        check(cudaMemset(s_.blocksDone, 0, sizeof(unsigned)), "memset");
        s_.particleStride = lanes_ == 1 ? 1 : kListCapacity;
        s_.entryStride = lanes_ == 1 ? s_.n : 1;
        parity_ = 0;
        persistentStep_ = 0;
        if (over_cells(design_)) {
            std::vector<int> identity(s_.n);
            std::iota(identity.begin(), identity.end(), 0);
            check(cudaMemcpy(s_.originalId, identity.data(), sizeof(int) * s_.n, cudaMemcpyHostToDevice), "copy");
            // Enough parts per cell (or group) that one of average size takes one round of members.
            const int membersPerRound = over_half_cells(design_) ? kHalfMembersPerRound : kCellThreads / lanes_;
            const int tiles = over_half_cells(design_) ? half_cell_groups() : s_.cells;
            parts_ = std::max(1, (s_.n / tiles + membersPerRound - 1) / membersPerRound);
            launch_cells_build(s_, s_.pos[0], stream_);
        } else {
            launch_build(s_, s_.pos[0], stream_);
        }
        check(cudaMemsetAsync(s_.builds, 0, sizeof(int), stream_), "memset");
        check(cudaStreamSynchronize(stream_), "initial build");
    }

    // The forces at step 0 into `forceOut`, and the first step's half: chain computes f(0);
    // fused and persistent take the first step without its closing kick, so that every later step
    // repeats chain's arithmetic (chain's state x(n), v(n), f(n) against their x(n+1), v(n+1/2)).
    void start(float4* forceOut) {
        with_lanes(lanes_, [&](auto lanes) {
            constexpr int L = decltype(lanes)::value;
            const int blocks = blocks_for(static_cast<long long>(s_.n) * L);
            if (design_ == Design::kChain) {
                chain_pair<L><<<blocks, kThreads, 0, stream_>>>(s_);
                check(cudaMemcpyAsync(forceOut, s_.force, sizeof(float4) * s_.n, cudaMemcpyDeviceToDevice, stream_), "copy");
            } else if (design_ == Design::kFused) {
                fused_step<L><<<blocks, kThreads, 0, stream_>>>(s_, s_.pos[0], s_.pos[1], false, 0, forceOut);
                check(cudaStreamSynchronize(stream_), "first fused step");
                if (read_one(s_.rebuild)) launch_build(s_, s_.pos[1], stream_);
                parity_ = 1;
            } else if (design_ == Design::kCellsFused) {
                cells_fused_step<L><<<s_.cells * parts_, kCellThreads, 0, stream_>>>(s_, s_.pos[0], s_.pos[1], parts_,
                                                                                     false, 0, forceOut);
                check(cudaStreamSynchronize(stream_), "first fused step over cells");
                if (read_one(s_.rebuild)) launch_cells_build(s_, s_.pos[1], stream_);
                parity_ = 1;
            } else if (design_ == Design::kHalfCellsFused) {
                half_cells_fused_step<L><<<tile_items(), kHalfMembersPerRound * L, 0, stream_>>>(
                    s_, s_.pos[0], s_.pos[1], parts_, false, 0, forceOut);
                check(cudaStreamSynchronize(stream_), "first fused step over half cells");
                if (read_one(s_.rebuild)) launch_cells_build(s_, s_.pos[1], stream_);
                parity_ = 1;
            } else if (design_ == Design::kCellsPersistent) {
                launch_cells_persistent<L>(1, false, forceOut);
            } else if (design_ == Design::kHalfCellsPersistent) {
                launch_half_cells_persistent<L>(1, false, forceOut);
            } else {
                launch_persistent<L>(1, false, forceOut);
            }
        });
        check(cudaStreamSynchronize(stream_), "first step");
        if (!persistent(design_)) exec_ = capture(stepsPerGraph_);
    }

    // Steps on: a multiple of kStepsPerGraph for the graph designs but chain's.
    void run(int steps) {
        if (design_ == Design::kPersistent) {
            with_lanes(lanes_, [&](auto lanes) { launch_persistent<decltype(lanes)::value>(steps, true, nullptr); });
            return;
        }
        if (design_ == Design::kCellsPersistent) {
            with_lanes(lanes_,
                       [&](auto lanes) { launch_cells_persistent<decltype(lanes)::value>(steps, true, nullptr); });
            return;
        }
        if (design_ == Design::kHalfCellsPersistent) {
            with_lanes(lanes_,
                       [&](auto lanes) { launch_half_cells_persistent<decltype(lanes)::value>(steps, true, nullptr); });
            return;
        }
        const int remainder = steps % stepsPerGraph_;
        if (remainder && remainder != remainderSteps_) {  // captured before the steps, outside their time
            check(cudaStreamSynchronize(stream_), "steps before a capture");
            if (remainderExec_) cudaGraphExecDestroy(remainderExec_);
            remainderExec_ = capture(remainder);
            remainderSteps_ = remainder;
        }
        for (int done = 0; done + stepsPerGraph_ <= steps; done += stepsPerGraph_)
            check(cudaGraphLaunch(exec_, stream_), "graph launch");
        if (remainder) check(cudaGraphLaunch(remainderExec_, stream_), "graph launch");
    }

    // The positions one drift after the state, x(n+1), by original particle id: chain's are drifted on
    // scratch copies by its own drift kernel, the others hold them already (in cell order over cells).
    std::vector<float4> next_positions() {
        if (over_cells(design_)) {
            const std::vector<float4> sorted = to_host(s_.pos[parity_], s_.n);
            const std::vector<int> id = to_host(s_.originalId, s_.n);
            std::vector<float4> next(s_.n);
            for (int i = 0; i < s_.n; ++i) next[id[i]] = sorted[i];
            return next;
        }
        if (design_ != Design::kChain) return to_host(s_.pos[parity_], s_.n);
        float4 *pos = device_array<float4>(s_.n), *vel = device_array<float4>(s_.n);
        int* flag = device_array<int>(1);
        check(cudaMemcpy(pos, s_.pos[0], sizeof(float4) * s_.n, cudaMemcpyDeviceToDevice), "copy");
        check(cudaMemcpy(vel, s_.vel, sizeof(float4) * s_.n, cudaMemcpyDeviceToDevice), "copy");
        chain_drift<<<blocks_for(s_.n), kThreads>>>(s_, pos, vel, flag);
        std::vector<float4> next = to_host(pos, s_.n);
        cudaFree(pos);
        cudaFree(vel);
        cudaFree(flag);
        return next;
    }

    double energy() const {
        return design_ == Design::kChain ? total_energy(s_, s_.pos[0], false) : total_energy(s_, s_.pos[parity_], true);
    }

private:
    int half_cell_groups() const {
        const int groupsPerEdge = half_cell_groups_per_edge(s_.perEdge);
        return groupsPerEdge * groupsPerEdge * groupsPerEdge;
    }
    // The blocks of one step over cells: a block per (cell or group, part).
    int tile_items() const { return (over_half_cells(design_) ? half_cell_groups() : s_.cells) * parts_; }

    template <int L>
    void launch_half_cells_persistent(int steps, bool closingFirst, float4* forceOut) {
        constexpr int kBlockThreads = kHalfMembersPerRound * L;
        if (!cooperativeBlocks_) {
            int perMultiprocessor = 0, multiprocessors = 0;
            check(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perMultiprocessor, half_cells_persistent_steps<L>,
                                                                kBlockThreads, 0),
                  "occupancy");
            check(cudaDeviceGetAttribute(&multiprocessors, cudaDevAttrMultiProcessorCount, 0), "device");
            cooperativeBlocks_ = std::max(1, std::min(perMultiprocessor * multiprocessors, tile_items()));
        }
        int parity = parity_, parts = parts_;
        long long firstStep = persistentStep_;
        void* args[] = {&s_, &parity, &firstStep, &steps, &parts, &closingFirst, &forceOut};
        check(cudaLaunchCooperativeKernel(reinterpret_cast<void*>(half_cells_persistent_steps<L>),
                                          dim3(cooperativeBlocks_), dim3(kBlockThreads), args, 0, stream_),
              "cooperative launch");
        parity_ = (parity_ + steps) & 1;
        persistentStep_ += steps;
    }

    template <int L>
    void launch_cells_persistent(int steps, bool closingFirst, float4* forceOut) {
        if (!cooperativeBlocks_) {
            int perMultiprocessor = 0, multiprocessors = 0;
            check(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perMultiprocessor, cells_persistent_steps<L>,
                                                                kCellThreads, 0),
                  "occupancy");
            check(cudaDeviceGetAttribute(&multiprocessors, cudaDevAttrMultiProcessorCount, 0), "device");
            cooperativeBlocks_ = std::max(1, std::min(perMultiprocessor * multiprocessors, s_.cells * parts_));
        }
        int parity = parity_, parts = parts_;
        long long firstStep = persistentStep_;
        void* args[] = {&s_, &parity, &firstStep, &steps, &parts, &closingFirst, &forceOut};
        check(cudaLaunchCooperativeKernel(reinterpret_cast<void*>(cells_persistent_steps<L>), dim3(cooperativeBlocks_),
                                          dim3(kCellThreads), args, 0, stream_),
              "cooperative launch");
        parity_ = (parity_ + steps) & 1;
        persistentStep_ += steps;
    }

    template <int L>
    void launch_persistent(int steps, bool closingFirst, float4* forceOut) {
        if (!cooperativeBlocks_) {
            int perMultiprocessor = 0, multiprocessors = 0;
            check(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perMultiprocessor, persistent_steps<L>, kThreads, 0),
                  "occupancy");
            check(cudaDeviceGetAttribute(&multiprocessors, cudaDevAttrMultiProcessorCount, 0), "device");
            cooperativeBlocks_ = std::max(1, std::min(perMultiprocessor * multiprocessors,
                                                      blocks_for(static_cast<long long>(s_.n) * L)));
        }
        int parity = parity_;
        long long firstStep = persistentStep_;
        void* args[] = {&s_, &parity, &firstStep, &steps, &closingFirst, &forceOut};
        check(cudaLaunchCooperativeKernel(reinterpret_cast<void*>(persistent_steps<L>), dim3(cooperativeBlocks_),
                                          dim3(kThreads), args, 0, stream_),
              "cooperative launch");
        parity_ = (parity_ + steps) & 1;
        persistentStep_ += steps;
    }

    // A graph of `steps` steps.
    cudaGraphExec_t capture(int steps) {
        cudaGraph_t graph = nullptr;
        cudaGraphExec_t exec = nullptr;
        check(cudaStreamBeginCapture(stream_, cudaStreamCaptureModeThreadLocal), "begin capture");
        with_lanes(lanes_, [&](auto lanes) {
            constexpr int L = decltype(lanes)::value;
            const int pairBlocks = blocks_for(static_cast<long long>(s_.n) * L), particleBlocks = blocks_for(s_.n);
            for (int step = 0; step < steps; ++step) {
                cudaGraphConditionalHandle handle{};
                check(cudaGraphConditionalHandleCreate(&handle, capturing_graph(stream_), 0, 0), "graph condition");
                if (design_ == Design::kChain) {
                    launch(chain_clock, 1, 1, stream_, step > 0, s_);
                    launch(chain_drift, particleBlocks, kThreads, stream_, true, s_, s_.pos[0], s_.vel, s_.rebuild);
                    launch(chain_set_condition, 1, 1, stream_, true, s_, handle);
                    capture_if(stream_, bodyStream_, handle, [&](cudaStream_t body) { launch_build(s_, s_.pos[0], body); });
                    launch(chain_pair<L>, pairBlocks, kThreads, stream_, false, s_);
                    launch(chain_kick, particleBlocks, kThreads, stream_, true, s_);
                } else if (design_ == Design::kCellsFused) {
                    const float4* in = s_.pos[(parity_ + step) & 1];
                    float4* out = s_.pos[(parity_ + step + 1) & 1];
                    launch(cells_fused_step<L>, s_.cells * parts_, kCellThreads, stream_, false, s_, in, out, parts_,
                           true, handle, static_cast<float4*>(nullptr));
                    capture_if(stream_, bodyStream_, handle,
                               [&](cudaStream_t body) { launch_cells_build(s_, out, body); });
                } else if (design_ == Design::kHalfCellsFused) {
                    const float4* in = s_.pos[(parity_ + step) & 1];
                    float4* out = s_.pos[(parity_ + step + 1) & 1];
                    launch(half_cells_fused_step<L>, tile_items(), kHalfMembersPerRound * L, stream_, false, s_, in,
                           out, parts_, true, handle, static_cast<float4*>(nullptr));
                    capture_if(stream_, bodyStream_, handle,
                               [&](cudaStream_t body) { launch_cells_build(s_, out, body); });
                } else {
                    const float4* in = s_.pos[(parity_ + step) & 1];
                    float4* out = s_.pos[(parity_ + step + 1) & 1];
                    launch(fused_step<L>, pairBlocks, kThreads, stream_, false, s_, in, out, true, handle,
                           static_cast<float4*>(nullptr));
                    capture_if(stream_, bodyStream_, handle, [&](cudaStream_t body) { launch_build(s_, out, body); });
                }
            }
        });
        check(cudaStreamEndCapture(stream_, &graph), "end capture");
        check(cudaGraphInstantiate(&exec, graph, 0), "instantiate");
        check(cudaGraphUpload(exec, stream_), "upload");
        cudaGraphDestroy(graph);
        return exec;
    }

    Design design_;
    int lanes_;
    int stepsPerGraph_;
    System& s_;
    cudaStream_t stream_, bodyStream_;
    cudaGraphExec_t exec_ = nullptr;
    cudaGraphExec_t remainderExec_ = nullptr;  // chain-g16: the graph of a run's last steps
    int remainderSteps_ = 0;
    int parity_ = 0;
    long long persistentStep_ = 0;
    int cooperativeBlocks_ = 0;
    int parts_ = 1;  // cell tiles: blocks per home cell
};

// The engine's lanes for a pair kernel (kNeighbourSum): the most that keep the particles' threads
// within half the resident threads of the device.
int engine_lanes(int n) {
    int multiprocessors = 0, threadsPerMultiprocessor = 0;
    check(cudaDeviceGetAttribute(&multiprocessors, cudaDevAttrMultiProcessorCount, 0), "device");
    check(cudaDeviceGetAttribute(&threadsPerMultiprocessor, cudaDevAttrMaxThreadsPerMultiProcessor, 0), "device");
    const long long resident = static_cast<long long>(multiprocessors) * threadsPerMultiprocessor;
    int lanes = 1;
    while (lanes < 32 && 2ll * n * lanes <= resident / 2) lanes *= 2;
    return lanes;
}

struct Options {
    int steps = 2000;
    int warmup = 200;
    int checkSteps = 100;
    std::string csv;
    std::vector<int> sizes;
    std::vector<std::string> only;  // name prefixes of the variants to run; empty: all

    // chain always runs: its positions are the other variants' trajectory reference.
    bool selected(const std::string& name) const {
        if (only.empty() || name == "chain") return true;
        return std::any_of(only.begin(), only.end(),
                           [&](const std::string& prefix) { return name.compare(0, prefix.size(), prefix) == 0; });
    }
};

int round_to_graphs(int steps) { return std::max(1, (steps + kStepsPerGraph - 1) / kStepsPerGraph) * kStepsPerGraph; }

struct Row {
    int n;
    std::string variant;
    int lanes, blocks;
    double usPerStep, stepsPerSecond, buildsPer1000, forceError, trajectoryError, energyDrift, neighbours;
};

// Largest |dF| over particles and components, in units of the sum of the particle's pair-force
// magnitudes (the scale of its round-off).
double relative_force_error(const std::vector<float4>& force, const Reference& r) {
    double worst = 0;
    for (size_t i = 0; i < force.size(); ++i) {
        const double scale = std::max(1.0, r.magnitudes[i]);
        worst = std::max({worst, std::fabs(force[i].x - r.force[i].x) / scale, std::fabs(force[i].y - r.force[i].y) / scale,
                          std::fabs(force[i].z - r.force[i].z) / scale});
    }
    return worst;
}

double largest_displacement(const std::vector<float4>& a, const std::vector<float4>& b, float length) {
    double worst = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const double d[3] = {double(a[i].x) - b[i].x, double(a[i].y) - b[i].y, double(a[i].z) - b[i].z};
        for (double c : d) worst = std::max(worst, std::fabs(c - length * std::rint(c / length)));
    }
    return worst;
}

// Forces: |dF| within 1e-4 of the pair forces' magnitude sum (a float pair force wrapped through the
// box carries ~1e-5 relative error; a missing or doubled pair is far larger). Trajectories: the
// same sum order repeats chain's arithmetic and should give 0; another order starts at round-off
// (~1e-6) and the liquid's chaos (Lyapunov exponent ~5 per tau) multiplies it by ~10 over 0.5 tau,
// well under 1e-3, while a force or kick in error moves particles by more within those steps.
constexpr double kForceTolerance = 1e-4;
constexpr double kTrajectoryTolerance = 1e-3;

// The tiles' mean size per particle: each cell's members see the cells around it (`reach` on
// each side).
double mean_candidates(const System& s, int reach) {
    const std::vector<int> start = to_host(s.cellStart, s.cells + 1);
    const int e = s.perEdge;
    double sum = 0;
    for (int cell = 0; cell < s.cells; ++cell) {
        const int cx = cell % e, cy = (cell / e) % e, cz = cell / (e * e);
        int tile = 0;
        for (int dz = -reach; dz <= reach; ++dz)
            for (int dy = -reach; dy <= reach; ++dy)
                for (int dx = -reach; dx <= reach; ++dx) {
                    const int neighbour = (((cz + dz + e) % e) * e + (cy + dy + e) % e) * e + (cx + dx + e) % e;
                    tile += start[neighbour + 1] - start[neighbour];
                }
        sum += static_cast<double>(start[cell + 1] - start[cell]) * tile;
    }
    return sum / s.n;
}

bool run_size(int cellsPerEdge, const Options& options, std::vector<Row>& rows) {
    const Liquid liquid = make_liquid(cellsPerEdge);
    if (liquid.perEdge < 3) {  // the 27 cells around one would not be distinct
        std::printf("# k = %d (%zu particles) skipped: fewer than 3 list cells per edge\n", cellsPerEdge,
                    liquid.pos.size());
        return true;
    }
    System s = make_system(liquid, liquid.perEdge);
    cudaStream_t stream, bodyStream;
    // The steps' stream synchronises with the legacy stream that the checks' copies and kernels use.
    check(cudaStreamCreate(&stream), "stream");
    check(cudaStreamCreateWithFlags(&bodyStream, cudaStreamNonBlocking), "stream");
    check(cudaMemcpy(s.pos[0], liquid.pos.data(), sizeof(float4) * s.n, cudaMemcpyHostToDevice), "copy");
    const Reference reference = reference_at(s, s.pos[0]);
    float4* firstForces = device_array<float4>(s.n);
    int* listedWithin = device_array<int>(s.n);
    const int checkSteps = round_to_graphs(options.checkSteps), warmup = round_to_graphs(options.warmup),
              steps = round_to_graphs(options.steps);

    const int chainLanes = engine_lanes(s.n);
    struct Spec {
        Design design;
        int lanes;
        int stepsPerGraph;
    };
    std::vector<Spec> designs = {{Design::kChain, chainLanes, kStepsPerGraph}};
    for (int lanes : {1, 2, 4, 8, 16, 32}) designs.push_back({Design::kFused, lanes, kStepsPerGraph});
    for (int lanes : {1, 2, 4, 8, 16, 32}) designs.push_back({Design::kPersistent, lanes, kStepsPerGraph});
    for (int lanes : {4, 8, 16, 32}) designs.push_back({Design::kCellsFused, lanes, kStepsPerGraph});
    for (int lanes : {4, 8, 16, 32}) designs.push_back({Design::kCellsPersistent, lanes, kStepsPerGraph});
    for (int lanes : {2, 4, 8}) designs.push_back({Design::kHalfCellsFused, lanes, kStepsPerGraph});
    for (int lanes : {2, 4, 8}) designs.push_back({Design::kHalfCellsPersistent, lanes, kStepsPerGraph});
    designs.push_back({Design::kChain, chainLanes, kEngineStepsPerGraph});

    // The half cells bin the same liquid into cells of edge >= kHalfCellEdge, in a system of their own.
    const int halfPerEdge = static_cast<int>(std::floor(liquid.length / kHalfCellEdge));
    System half;
    const bool anyHalf = std::any_of(designs.begin(), designs.end(), [&](const Spec& spec) {
        return over_half_cells(spec.design) && options.selected(variant_name(spec.design, spec.lanes, spec.stepsPerGraph));
    });
    if (anyHalf) half = make_system(liquid, halfPerEdge);  // 3+ list cells per edge: 6+ half cells

    bool passed = true;
    std::vector<float4> chainPositions;
    for (const auto& [design, lanes, stepsPerGraph] : designs) {
        if (!options.selected(variant_name(design, lanes, stepsPerGraph))) continue;
        System& vs = over_half_cells(design) ? half : s;  // the variant's system
        Variant variant(design, lanes, stepsPerGraph, vs, stream, bodyStream);
        variant.reset(liquid);
        double neighbours = 0;  // mean list length, or over cells the mean number of candidates
        if (over_cells(design)) {
            const int reach = over_half_cells(design) ? kHalfReach : 1;
            candidates_within_cutoff<<<blocks_for(vs.n), kThreads>>>(vs, vs.pos[0], listedWithin, reach);
            neighbours = mean_candidates(vs, reach);
        } else {
            listed_within_cutoff<<<blocks_for(s.n), kThreads>>>(s, s.pos[0], listedWithin);
            const std::vector<int> counts = to_host(s.listCount, s.n);
            neighbours = std::accumulate(counts.begin(), counts.end(), 0.0) / s.n;
        }
        const std::vector<int> listed = to_host(listedWithin, s.n);
        int listsMissingPairs = 0;
        for (int i = 0; i < s.n; ++i) listsMissingPairs += listed[i] != reference.withinCutoff[i];

        variant.start(firstForces);
        const double forceError = relative_force_error(to_host(firstForces, s.n), reference);
        variant.run(checkSteps);
        const std::vector<float4> positions = variant.next_positions();
        if (design == Design::kChain && stepsPerGraph == kStepsPerGraph) chainPositions = positions;
        const double trajectoryError = largest_displacement(positions, chainPositions, s.length);

        variant.run(warmup);
        check(cudaStreamSynchronize(stream), "warm-up");
        const double energyBefore = variant.energy();
        const int buildsBefore = read_one(vs.builds);
        cudaEvent_t begin, end;
        check(cudaEventCreate(&begin), "event");
        check(cudaEventCreate(&end), "event");
        check(cudaEventRecord(begin, stream), "event");
        variant.run(steps);
        check(cudaEventRecord(end, stream), "event");
        check(cudaEventSynchronize(end), variant.name().c_str());
        float ms = 0;
        check(cudaEventElapsedTime(&ms, begin, end), "event");
        cudaEventDestroy(begin);
        cudaEventDestroy(end);
        const int builds = read_one(vs.builds) - buildsBefore;
        const double energyAfter = variant.energy();
        const int overflow = read_one(vs.overflow);

        const double us = 1000.0 * ms / steps;
        rows.push_back({s.n, variant.name(), lanes, variant.grid(), us, 1e6 / us, 1000.0 * builds / steps, forceError,
                        trajectoryError, (energyAfter - energyBefore) / s.n, neighbours});
        const Row& r = rows.back();
        std::printf("%9d  %-23s %5d %7d %9.2f %11.0f %8.1f %10.2e %10.2e %11.2e %6.1f\n", r.n, r.variant.c_str(), r.lanes,
                    r.blocks, r.usPerStep, r.stepsPerSecond, r.buildsPer1000, r.forceError, r.trajectoryError,
                    r.energyDrift, r.neighbours);
        std::fflush(stdout);
        if (listsMissingPairs || forceError > kForceTolerance || trajectoryError > kTrajectoryTolerance || overflow) {
            std::fprintf(stderr,
                         "%s at %d particles failed: %d lists (or tiles) differ from the reference's pairs within rc, "
                         "force error %.2e (tolerance %.0e), positions %.2e from chain's (tolerance %.0e), %d overflows\n",
                         r.variant.c_str(), s.n, listsMissingPairs, forceError, kForceTolerance, trajectoryError,
                         kTrajectoryTolerance, overflow);
            passed = false;
        }
    }
    cudaFree(firstForces);
    cudaFree(listedWithin);
    cudaStreamDestroy(stream);
    cudaStreamDestroy(bodyStream);
    free_system(s);
    if (anyHalf) free_system(half);
    return passed;
}

Options parse(int argc, char** argv) {
    Options options;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        auto value = [&] {
            if (a + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", arg.c_str());
                std::exit(2);
            }
            return std::string(argv[++a]);
        };
        if (arg == "--steps")
            options.steps = std::stoi(value());
        else if (arg == "--warmup")
            options.warmup = std::stoi(value());
        else if (arg == "--check-steps")
            options.checkSteps = std::stoi(value());
        else if (arg == "--csv")
            options.csv = value();
        else if (arg == "--only") {
            const std::string list = value();
            for (size_t begin = 0; begin <= list.size();) {
                const size_t end = std::min(list.find(',', begin), list.size());
                if (end > begin) options.only.push_back(list.substr(begin, end - begin));
                begin = end + 1;
            }
        }
        else if (!arg.empty() && arg[0] != '-')
            options.sizes.push_back(std::stoi(arg));
        else {
            std::fprintf(stderr,
                         "usage: %s [--steps S] [--warmup W] [--check-steps C] [--csv PATH] [--only P1,P2,...] "
                         "[cells per edge ...]\n",
                         argv[0]);
            std::exit(2);
        }
    }
    if (options.sizes.empty()) options.sizes = {10, 14, 25};
    return options;
}

}  // namespace

int main(int argc, char** argv) {
    const Options options = parse(argc, argv);
    cudaDeviceProp prop{};
    check(cudaGetDeviceProperties(&prop, 0), "device");
    int cooperative = 0;
    check(cudaDeviceGetAttribute(&cooperative, cudaDevAttrCooperativeLaunch, 0), "device");
    if (!cooperative) {
        std::fprintf(stderr, "%s cannot launch cooperative kernels\n", prop.name);
        return 1;
    }
    std::printf("# %s; timed steps %d after %d warm-up steps, trajectories compared after %d steps\n", prop.name,
                round_to_graphs(options.steps), round_to_graphs(options.warmup), round_to_graphs(options.checkSteps));
    std::printf("%9s  %-23s %5s %7s %9s %11s %8s %10s %10s %11s %6s\n", "particles", "variant", "lanes", "blocks",
                "us/step", "steps/s", "builds", "max|dF|", "max|dx|", "dE/N", "list");
    std::vector<Row> rows;
    bool passed = true;
    for (int k : options.sizes) passed = run_size(k, options, rows) && passed;
    if (!options.csv.empty()) {
        FILE* out = std::fopen(options.csv.c_str(), "w");
        if (!out) {
            std::fprintf(stderr, "cannot write %s\n", options.csv.c_str());
            return 1;
        }
        std::fprintf(out,
                     "particles,variant,lanes,blocks,us_per_step,steps_per_s,builds_per_1000_steps,max_force_error,"
                     "max_position_difference,energy_drift_per_particle,mean_list_length\n");
        for (const Row& r : rows)
            std::fprintf(out, "%d,%s,%d,%d,%.4f,%.1f,%.2f,%.3e,%.3e,%.4e,%.2f\n", r.n, r.variant.c_str(), r.lanes,
                         r.blocks, r.usPerStep, r.stepsPerSecond, r.buildsPer1000, r.forceError, r.trajectoryError,
                         r.energyDrift, r.neighbours);
        std::fclose(out);
    }
    if (!passed) std::fprintf(stderr, "some variant failed its checks; its timings are not to be used\n");
    return passed ? 0 : 1;
}
