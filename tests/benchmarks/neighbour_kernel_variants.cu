// Neighbour-kernel design study for issue 12: what a half neighbour list (Newton's third law), a
// space-filling order of the cells and a cell-wise list build would buy structmd before the engine
// is rewritten for them. Standalone (no engine code), so each variant is the bare kernel. Forces:
//   full          every pair twice, one thread per particle, no atomics (structmd's kernel at large N)
//   full-table    as full, the pair's parameters looked up by type for every neighbour
//   full-scatter  as full, the force added to the particle's entry through a permutation of slots
//   full-both     both of the above, as the engine's generic pair kernel does
//   half-float    every pair once, the j side added with float atomics (not reproducible run to run)
//   half-fixed    every pair once, all sides added as 64-bit fixed-point integer atomics, which are
//                 reproducible (integer sums do not depend on their order), then converted to float
// Lists (all full):
//   build-thread  a thread per particle walks the 27 cells around it (the engine's build)
//   build-shfl    a warp per cell, candidates loaded once per round of 32 and shuffled to the lanes
//   build-smem    the same through shared memory
//   build-staged  build-shfl keeping the lists in shared memory until written out whole
// over an LJ liquid (fcc at density 0.8442, jittered), rc 2.5, list radius 2.8, particles sorted by
// cell in row order (x fastest) or in Morton order of the cells. Lists are stored by columns (entry m
// of consecutive particles side by side), as structmd stores them for one thread per particle.
// Each variant is checked before it is timed: forces against the full list's, lists entry by entry
// against build-thread's.
//
//   structmd_neighbour_kernel_variants [cells per edge of the fcc lattice ...]
//   (default 14 25 63 100 159: 10,976 to 16,078,716 particles, the sizes of issue 12)
#include <cuda_runtime.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include "backends/cuda/launch_kernels.cuh"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/pair_kernel.hpp"
#include "standalone_cuda.cuh"

namespace {

using standalone::check;

constexpr float kCutoff2 = 2.5f * 2.5f;
constexpr float kListRadius = 2.8f;
constexpr double kFixedScale = 4294967296.0;  // 2^32: forces to 2.3e-10, magnitudes to 2^31

struct Liquid {
    std::vector<float4> pos;  // wrapped into [0, L)
    float length = 0;
};

Liquid fcc_liquid(int cellsPerEdge) {
    Liquid liquid;
    const double a = std::cbrt(4.0 / 0.8442);
    liquid.length = static_cast<float>(a * cellsPerEdge);
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    uint64_t state = 12345;
    auto jitter = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return 0.1 * (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5);
    };
    for (int x = 0; x < cellsPerEdge; ++x)
        for (int y = 0; y < cellsPerEdge; ++y)
            for (int z = 0; z < cellsPerEdge; ++z)
                for (const auto& b : basis) {
                    auto wrap = [&](double v) { return static_cast<float>(std::fmod(v + 10 * liquid.length, liquid.length)); };
                    liquid.pos.push_back({wrap((x + b[0]) * a + jitter()), wrap((y + b[1]) * a + jitter()),
                                          wrap((z + b[2]) * a + jitter()), 0.f});
                }
    return liquid;
}

uint64_t spread_bits(uint64_t v) {
    uint64_t r = 0;
    for (int bit = 0; bit < 21; ++bit) r |= ((v >> bit) & 1ull) << (3 * bit);
    return r;
}

struct Cells {
    int perEdge = 0;
    std::vector<int> rank;      // the position of each row-order cell in the chosen order
    std::vector<int> linearOf;  // the row-order cell at each position of the chosen order
    std::vector<int> start;  // first slot of each cell, by rank
};

// Sorts the particles by cell, cells in row order or in Morton order, and returns the cell ranges.
Cells sort_by_cell(Liquid& liquid, bool morton) {
    Cells cells;
    cells.perEdge = static_cast<int>(std::floor(liquid.length / kListRadius));
    const int n = cells.perEdge, count = n * n * n;
    std::vector<int> byOrder(count);
    std::iota(byOrder.begin(), byOrder.end(), 0);
    if (morton)
        std::sort(byOrder.begin(), byOrder.end(), [n](int p, int q) {
            auto key = [n](int c) {
                return spread_bits(c % n) | spread_bits((c / n) % n) << 1 | spread_bits(c / (n * n)) << 2;
            };
            return key(p) < key(q);
        });
    cells.rank.assign(count, 0);
    for (int r = 0; r < count; ++r) cells.rank[byOrder[r]] = r;
    cells.linearOf = byOrder;
    auto cell_of = [&](const float4& p) {
        auto c = [&](float v) { return std::min(n - 1, static_cast<int>(v / liquid.length * n)); };
        return cells.rank[(c(p.z) * n + c(p.y)) * n + c(p.x)];
    };
    cells.start.assign(count + 1, 0);
    for (const float4& p : liquid.pos) ++cells.start[cell_of(p) + 1];
    std::partial_sum(cells.start.begin(), cells.start.end(), cells.start.begin());
    std::vector<int> next(cells.start.begin(), cells.start.end() - 1);
    std::vector<float4> sorted(liquid.pos.size());
    for (const float4& p : liquid.pos) sorted[next[cell_of(p)]++] = p;
    liquid.pos.swap(sorted);
    return cells;
}

__device__ float3 minimum_image(float3 d, float length) {
    d.x -= length * rintf(d.x / length);
    d.y -= length * rintf(d.y / length);
    d.z -= length * rintf(d.z / length);
    return d;
}

__device__ float3 lj_force(float3 d) {  // on i from j, d = r_i - r_j
    const float r2 = d.x * d.x + d.y * d.y + d.z * d.z;
    if (r2 >= kCutoff2) return {0, 0, 0};
    const float inv2 = 1.f / r2, inv6 = inv2 * inv2 * inv2;
    const float scale = 24.f * inv2 * inv6 * (2.f * inv6 - 1.f);
    return {scale * d.x, scale * d.y, scale * d.z};
}

// One thread per particle: its neighbours (all, or only those after it in slot order) from the 27
// cells around its own, by columns.
__global__ void build_lists(int n, const float4* pos, float length, int perEdge, const int* rank, const int* start,
                            bool half, int capacity, int* list, int* count, int* overflow) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    const float4 p = pos[i];
    auto c = [&](float v) { return min(perEdge - 1, static_cast<int>(v / length * perEdge)); };
    const int cx = c(p.x), cy = c(p.y), cz = c(p.z);
    int found = 0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                auto wrap = [&](int v) { return (v + perEdge) % perEdge; };
                const int cell = rank[(wrap(cz + dz) * perEdge + wrap(cy + dy)) * perEdge + wrap(cx + dx)];
                for (int j = start[cell]; j < start[cell + 1]; ++j) {
                    if (j == i || (half && j < i)) continue;
                    const float4 q = pos[j];
                    const float3 d = minimum_image(make_float3(q.x - p.x, q.y - p.y, q.z - p.z), length);
                    if (d.x * d.x + d.y * d.y + d.z * d.z < kListRadius * kListRadius) {
                        if (found < capacity) list[static_cast<int64_t>(found) * n + i] = j;
                        ++found;
                    }
                }
            }
    count[i] = found;
    if (found > capacity) atomicAdd(overflow, 1);
}

// One warp per cell: the lanes take the cell's members (32 at a time) and the candidates of each
// adjacent cell are loaded once per round of 32, one per lane, then handed to every lane, through
// shuffles or through shared memory. The periodic image of an adjacent cell is one shift for all
// its candidates, so no candidate needs a minimum-image fold. Lists come out identical to
// build_lists' (same cells in the same order, candidates in slot order).
// Staged: each lane keeps its list in shared memory (2 warps a block) and the warp writes the lists
// out row by row at the end, each row one coalesced line, instead of scattering single entries.
template <bool SharedMemory, bool Staged = false>
__global__ void build_lists_by_cell(int n, const float4* pos, float length, int perEdge, const int* rank,
                                    const int* linearOf, const int* start, int capacity, int* list, int* count) {
    __shared__ float4 tile[4][32];
    extern __shared__ int staged[];  // Staged: [warp in block][entry][lane]
    int* own = staged + (threadIdx.x / 32) * 32 * capacity;
    const int warp = (blockIdx.x * blockDim.x + threadIdx.x) / 32, lane = threadIdx.x % 32;
    const int cells = perEdge * perEdge * perEdge;
    if (warp >= cells) return;
    float4* candidates = tile[threadIdx.x / 32];
    const int linear = linearOf[warp];
    const int cx = linear % perEdge, cy = (linear / perEdge) % perEdge, cz = linear / (perEdge * perEdge);
    const float listRadius2 = kListRadius * kListRadius;
    for (int base = start[warp]; base < start[warp + 1]; base += 32) {
        const int i = base + lane;
        const bool member = i < start[warp + 1];
        const float4 p = member ? pos[i] : make_float4(0, 0, 0, 0);
        int found = 0;
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    auto wrap = [&](int v, float& shift) {
                        shift = v < 0 ? -length : (v >= perEdge ? length : 0.f);
                        return v < 0 ? v + perEdge : (v >= perEdge ? v - perEdge : v);
                    };
                    float sx, sy, sz;
                    const int ux = wrap(cx + dx, sx), uy = wrap(cy + dy, sy), uz = wrap(cz + dz, sz);
                    const int cell = rank[(uz * perEdge + uy) * perEdge + ux];
                    const int first = start[cell], last = start[cell + 1];
                    for (int round = first; round < last; round += 32) {
                        // This lane's candidate of the round, moved to the image next to the cell.
                        float4 q = round + lane < last ? pos[round + lane] : make_float4(0, 0, 0, 0);
                        q.x += sx;
                        q.y += sy;
                        q.z += sz;
                        if (SharedMemory) {
                            __syncwarp();
                            candidates[lane] = q;
                            __syncwarp();
                        }
                        const int inRound = min(32, last - round);
                        for (int t = 0; t < inRound; ++t) {
                            const float4 c = SharedMemory ? candidates[t]
                                                          : make_float4(__shfl_sync(0xffffffffu, q.x, t),
                                                                        __shfl_sync(0xffffffffu, q.y, t),
                                                                        __shfl_sync(0xffffffffu, q.z, t), 0.f);
                            const float x = c.x - p.x, y = c.y - p.y, z = c.z - p.z;
                            const int j = round + t;
                            if (member && j != i && x * x + y * y + z * z < listRadius2) {
                                if (found < capacity) {
                                    if (Staged)
                                        own[found * 32 + lane] = j;
                                    else
                                        list[static_cast<int64_t>(found) * n + i] = j;
                                }
                                ++found;
                            }
                        }
                    }
                }
        if (member) count[i] = found;
        if (Staged) {
            int longest = min(found, capacity);
            for (int offset = 16; offset > 0; offset /= 2) longest = max(longest, __shfl_xor_sync(0xffffffffu, longest, offset));
            __syncwarp();
            for (int m = 0; m < longest; ++m)
                if (member && m < found) list[static_cast<int64_t>(m) * n + i] = own[m * 32 + lane];
            __syncwarp();
        }
    }
}

__global__ void full_forces(int n, const float4* pos, float length, const int* list, const int* count, float4* force) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    const float4 p = pos[i];
    float3 f = {0, 0, 0};
    const int m = count[i];
#pragma unroll 4
    for (int k = 0; k < m; ++k) {
        const float4 q = pos[list[static_cast<int64_t>(k) * n + i]];
        const float3 d = lj_force(minimum_image(make_float3(p.x - q.x, p.y - q.y, p.z - q.z), length));
        f.x += d.x;
        f.y += d.y;
        f.z += d.z;
    }
    force[i] = make_float4(f.x, f.y, f.z, 0.f);
}

// The full kernel with what structmd's generic pair kernel adds to it (forcefield/pair_kernel.hpp):
// the parameters of each pair looked up by the neighbour's type (a table of one type here), and the
// force added to the particle's own entry, found through the slot's particle, which the drift
// kernel cleared to the external forces.
template <bool Table, bool Scatter>
__global__ void full_forces_engine_like(int n, const float4* pos, float length, const int* list, const int* count,
                                        const float4* table, const int* order, float4* force) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    const float4 p = pos[i];
    const float4* row = table + static_cast<int>(p.w);
    float3 f = {0, 0, 0};
    const int m = count[i];
#pragma unroll 4
    for (int k = 0; k < m; ++k) {
        const float4 q = pos[list[static_cast<int64_t>(k) * n + i]];
        const float3 d = minimum_image(make_float3(p.x - q.x, p.y - q.y, p.z - q.z), length);
        const float r2 = d.x * d.x + d.y * d.y + d.z * d.z;
        const float4 params = Table ? row[static_cast<int>(q.w)] : make_float4(1.f, 1.f, kCutoff2, 0.f);
        if (!(r2 < params.z)) continue;
        const float inv2 = 1.f / r2, sr2 = params.y * inv2, sr6 = sr2 * sr2 * sr2;
        const float scale = -params.x * 24.f * (sr6 - 2.f * sr6 * sr6) * inv2;
        f.x += scale * d.x;
        f.y += scale * d.y;
        f.z += scale * d.z;
    }
    if (Scatter) {
        float4& own = force[order[i]];
        own = make_float4(own.x + f.x, own.y + f.y, own.z + f.z, own.w);
    } else {
        force[i] = make_float4(f.x, f.y, f.z, 0.f);
    }
}

__device__ unsigned long long fixed(float v) {
    return static_cast<unsigned long long>(__double2ll_rn(static_cast<double>(v) * kFixedScale));
}

// Adds v to particle j's force: float atomics on force, or fixed-point ones on fixedForce.
template <bool Fixed>
__device__ void add_force(int64_t j, float3 v, float4* force, unsigned long long* fixedForce) {
    if (Fixed) {
        atomicAdd(fixedForce + 3 * j, fixed(v.x));
        atomicAdd(fixedForce + 3 * j + 1, fixed(v.y));
        atomicAdd(fixedForce + 3 * j + 2, fixed(v.z));
    } else {
        atomicAdd(&force[j].x, v.x);
        atomicAdd(&force[j].y, v.y);
        atomicAdd(&force[j].z, v.z);
    }
}

template <bool Fixed>
__global__ void half_forces(int n, const float4* pos, float length, const int* list, const int* count, float4* force,
                            unsigned long long* fixedForce) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    const float4 p = pos[i];
    float3 f = {0, 0, 0};
    const int m = count[i];
#pragma unroll 4
    for (int k = 0; k < m; ++k) {
        const int j = list[static_cast<int64_t>(k) * n + i];
        const float4 q = pos[j];
        const float3 d = lj_force(minimum_image(make_float3(p.x - q.x, p.y - q.y, p.z - q.z), length));
        f.x += d.x;
        f.y += d.y;
        f.z += d.z;
        add_force<Fixed>(j, make_float3(-d.x, -d.y, -d.z), force, fixedForce);
    }
    add_force<Fixed>(i, f, force, fixedForce);
}

// Back to float4 and the accumulators cleared for the next evaluation, in one pass.
__global__ void fixed_to_float(int n, unsigned long long* fixedForce, float4* force) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    auto value = [&](int axis) {
        unsigned long long& slot = fixedForce[3 * static_cast<int64_t>(i) + axis];
        const float v = static_cast<float>(static_cast<double>(static_cast<long long>(slot)) / kFixedScale);
        slot = 0;
        return v;
    };
    force[i] = make_float4(value(0), value(1), value(2), 0.f);
}

template <class T>
T* device_copy(const std::vector<T>& host) {
    T* d = nullptr;
    check(cudaMalloc(&d, std::max<size_t>(1, host.size()) * sizeof(T)), "cudaMalloc");
    check(cudaMemcpy(d, host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice), "cudaMemcpy");
    return d;
}

struct DeviceList {
    int capacity = 0;
    int* list = nullptr;
    int* count = nullptr;
    double meanNeighbours = 0;
};

DeviceList make_list(int n, const float4* pos, float length, const Cells& cells, const int* rank, const int* start,
                     bool half) {
    // A half list by slot order is uneven (the first slot of a region keeps nearly all its
    // neighbours), so it gets the full list's capacity.
    const double expected = 4.18879 * kListRadius * kListRadius * kListRadius * 0.8442;
    const int capacity = static_cast<int>(1.4 * expected) + 16;
    DeviceList l;
    l.capacity = capacity;
    int* overflow = nullptr;
    check(cudaMalloc(&l.list, sizeof(int) * static_cast<size_t>(capacity) * n), "cudaMalloc list");
    check(cudaMalloc(&l.count, sizeof(int) * n), "cudaMalloc count");
    check(cudaMalloc(&overflow, sizeof(int)), "cudaMalloc");
    check(cudaMemset(overflow, 0, sizeof(int)), "cudaMemset");
    build_lists<<<(n + 127) / 128, 128>>>(n, pos, length, cells.perEdge, rank, start, half, capacity, l.list, l.count,
                                          overflow);
    int overflowed = 0;
    check(cudaMemcpy(&overflowed, overflow, sizeof(int), cudaMemcpyDeviceToHost), "build");
    if (overflowed) {
        std::fprintf(stderr, "list capacity %d exceeded by %d particles\n", capacity, overflowed);
        std::exit(1);
    }
    std::vector<int> counts(n);
    check(cudaMemcpy(counts.data(), l.count, sizeof(int) * n, cudaMemcpyDeviceToHost), "counts");
    l.meanNeighbours = std::accumulate(counts.begin(), counts.end(), 0.0) / n;
    cudaFree(overflow);
    return l;
}

// Microseconds per force evaluation, the median of five timings of `repeats` evaluations each.
template <class Evaluate>
double time_us(Evaluate&& evaluate, int repeats) {
    cudaEvent_t begin, end;
    cudaEventCreate(&begin);
    cudaEventCreate(&end);
    for (int w = 0; w < 20; ++w) evaluate();
    std::vector<double> samples;
    for (int s = 0; s < 5; ++s) {
        cudaEventRecord(begin);
        for (int r = 0; r < repeats; ++r) evaluate();
        cudaEventRecord(end);
        check(cudaEventSynchronize(end), "timing");
        float ms = 0;
        cudaEventElapsedTime(&ms, begin, end);
        samples.push_back(1000.0 * ms / repeats);
    }
    std::sort(samples.begin(), samples.end());
    cudaEventDestroy(begin);
    cudaEventDestroy(end);
    return samples[2];
}

double max_difference(const float4* a, const float4* b, int n) {
    std::vector<float4> ha(n), hb(n);
    check(cudaMemcpy(ha.data(), a, sizeof(float4) * n, cudaMemcpyDeviceToHost), "copy");
    check(cudaMemcpy(hb.data(), b, sizeof(float4) * n, cudaMemcpyDeviceToHost), "copy");
    double worst = 0;
    for (int i = 0; i < n; ++i)
        worst = std::max({worst, std::fabs(double(ha[i].x) - hb[i].x), std::fabs(double(ha[i].y) - hb[i].y),
                          std::fabs(double(ha[i].z) - hb[i].z)});
    return worst;
}

// The list builds, each checked entry by entry against build_lists' full list (the last column
// counts the particles whose lists differ).
void time_builds(int n, const float4* pos, float length, const Cells& cells, const int* rank, const int* start,
                 const DeviceList& reference, bool morton) {
    const int capacity = reference.capacity;
    int* linearOf = device_copy(cells.linearOf);
    int *list = nullptr, *count = nullptr, *overflow = nullptr;
    check(cudaMalloc(&overflow, sizeof(int)), "cudaMalloc");
    check(cudaMalloc(&list, sizeof(int) * static_cast<size_t>(capacity) * n), "cudaMalloc list");
    check(cudaMalloc(&count, sizeof(int) * n), "cudaMalloc count");
    const int cellCount = cells.perEdge * cells.perEdge * cells.perEdge;
    const int cellBlocks = (cellCount * 32 + 127) / 128;
    const int stagedBytes = 2 * 32 * capacity * static_cast<int>(sizeof(int));
    check(cudaFuncSetAttribute(build_lists_by_cell<false, true>, cudaFuncAttributeMaxDynamicSharedMemorySize, stagedBytes),
          "shared memory");
    std::vector<int> expectedList(static_cast<size_t>(capacity) * n), expectedCount(n), gotList(expectedList.size()),
        gotCount(n);
    check(cudaMemcpy(expectedList.data(), reference.list, sizeof(int) * expectedList.size(), cudaMemcpyDeviceToHost), "copy");
    check(cudaMemcpy(expectedCount.data(), reference.count, sizeof(int) * n, cudaMemcpyDeviceToHost), "copy");
    struct Variant {
        const char* name;
        std::function<void()> build;
    };
    const Variant variants[] = {
        {"build-thread",
         [&] { build_lists<<<(n + 127) / 128, 128>>>(n, pos, length, cells.perEdge, rank, start, false, capacity, list,
                                                     count, overflow); }},
        {"build-shfl",
         [&] { build_lists_by_cell<false><<<cellBlocks, 128>>>(n, pos, length, cells.perEdge, rank, linearOf, start,
                                                               capacity, list, count); }},
        {"build-smem",
         [&] { build_lists_by_cell<true><<<cellBlocks, 128>>>(n, pos, length, cells.perEdge, rank, linearOf, start,
                                                              capacity, list, count); }},
        {"build-staged",
         [&] { build_lists_by_cell<false, true><<<(cellCount * 32 + 63) / 64, 64, stagedBytes>>>(
                   n, pos, length, cells.perEdge, rank, linearOf, start, capacity, list, count); }}};
    for (const Variant& v : variants) {
        v.build();
        check(cudaDeviceSynchronize(), v.name);
        check(cudaMemcpy(gotList.data(), list, sizeof(int) * gotList.size(), cudaMemcpyDeviceToHost), "copy");
        check(cudaMemcpy(gotCount.data(), count, sizeof(int) * n, cudaMemcpyDeviceToHost), "copy");
        int differing = 0;
        for (int i = 0; i < n; ++i) {
            bool same = gotCount[i] == expectedCount[i];
            for (int m = 0; same && m < expectedCount[i]; ++m)
                same = gotList[static_cast<size_t>(m) * n + i] == expectedList[static_cast<size_t>(m) * n + i];
            differing += !same;
        }
        const double us = time_us(v.build, std::max(5, static_cast<int>(2e7 / n)));
        std::printf("%10d,%-6s,%-10s,%6.1f,%10.1f,%10.3e,%9d\n", n, morton ? "morton" : "rows", v.name,
                    reference.meanNeighbours, us, n / (us * 1e-6), differing);
    }
    cudaFree(linearOf);
    cudaFree(overflow);
    cudaFree(list);
    cudaFree(count);
}

void run(int cellsPerEdge, bool morton) {
    Liquid liquid = fcc_liquid(cellsPerEdge);
    const Cells cells = sort_by_cell(liquid, morton);
    const int n = static_cast<int>(liquid.pos.size());
    float4* pos = device_copy(liquid.pos);
    int* rank = device_copy(cells.rank);
    int* start = device_copy(cells.start);
    const DeviceList full = make_list(n, pos, liquid.length, cells, rank, start, false);
    const DeviceList half = make_list(n, pos, liquid.length, cells, rank, start, true);
    float4 *reference = nullptr, *force = nullptr;
    unsigned long long* fixedForce = nullptr;
    check(cudaMalloc(&reference, sizeof(float4) * n), "cudaMalloc");
    check(cudaMalloc(&force, sizeof(float4) * n), "cudaMalloc");
    check(cudaMalloc(&fixedForce, sizeof(unsigned long long) * 3 * n), "cudaMalloc");
    check(cudaMemset(fixedForce, 0, sizeof(unsigned long long) * 3 * n), "cudaMemset");
    const int blocks = (n + 127) / 128;
    const int repeats = std::max(20, static_cast<int>(2e8 / (n * full.meanNeighbours)));

    auto evaluate_full = [&] { full_forces<<<blocks, 128>>>(n, pos, liquid.length, full.list, full.count, force); };
    auto evaluate_half_float = [&] {
        cudaMemsetAsync(force, 0, sizeof(float4) * n);
        half_forces<false><<<blocks, 128>>>(n, pos, liquid.length, half.list, half.count, force, fixedForce);
    };
    auto evaluate_half_fixed = [&] {
        half_forces<true><<<blocks, 128>>>(n, pos, liquid.length, half.list, half.count, force, fixedForce);
        fixed_to_float<<<blocks, 128>>>(n, fixedForce, force);
    };
    full_forces<<<blocks, 128>>>(n, pos, liquid.length, full.list, full.count, reference);
    struct Variant {
        const char* name;
        double neighbours;
        std::function<void()> evaluate;
    };
    std::vector<int> shuffled(n);
    std::iota(shuffled.begin(), shuffled.end(), 0);
    uint64_t state = 99;
    for (int a = n - 1; a > 0; --a) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        std::swap(shuffled[a], shuffled[static_cast<int>((state >> 33) % (a + 1))]);
    }
    int* order = device_copy(shuffled);
    float4* table = device_copy(std::vector<float4>{make_float4(1.f, 1.f, kCutoff2, 0.f)});
    float4* scattered = nullptr;
    check(cudaMalloc(&scattered, sizeof(float4) * n), "cudaMalloc");
    // The scattered variants add to forces cleared beforehand; their check gathers them back to slots.
    auto engine_like = [&](auto kernel, float4* out) {
        return [=] {
            cudaMemsetAsync(out, 0, sizeof(float4) * n);
            kernel<<<blocks, 128>>>(n, pos, liquid.length, full.list, full.count, table, order, out);
        };
    };
    // The engine's own pair kernel (forcefield/pair_kernel.hpp) through its own launch for one lane
    // per particle, over the same list: what the study's variants are compared with.
    using structmd::LennardJonesType1;
    using EnginePair = structmd::PairKernel<LennardJonesType1, float, float, true, false, false>;
    const structmd::LennardJonesParams<float> ljParams =
        LennardJonesType1::make_pair_params<float>(1.0, 1.0, 2.5, false);
    structmd::LennardJonesParams<float>* ljTable = device_copy(std::vector<structmd::LennardJonesParams<float>>{ljParams});
    // The engine reads a list by columns of chunks (neighbour/neighbour_view.hpp): the study's list,
    // by columns of single entries, laid out so.
    constexpr int kChunk = structmd::NeighbourView<float>::kChunk;
    const int engineCapacity = (full.capacity + kChunk - 1) / kChunk * kChunk;
    std::vector<int> columns(static_cast<size_t>(full.capacity) * n), chunked(static_cast<size_t>(engineCapacity) * n);
    check(cudaMemcpy(columns.data(), full.list, sizeof(int) * columns.size(), cudaMemcpyDeviceToHost), "list to host");
    for (int64_t i = 0; i < n; ++i)
        for (int64_t m = 0; m < full.capacity; ++m)
            chunked[(m / kChunk) * kChunk * n + i * kChunk + m % kChunk] = columns[m * n + i];
    int* engineList = device_copy(chunked);
    EnginePair engine{};
    engine.neighbours.positions = reinterpret_cast<const structmd::Real4<float>*>(pos);
    engine.neighbours.binned = engine.neighbours.positions;
    engine.neighbours.order = order;
    engine.neighbours.list = engineList;
    engine.neighbours.count = full.count;
    engine.neighbours.capacity = engineCapacity;
    engine.neighbours.particleStride = kChunk;
    engine.neighbours.chunkStride = static_cast<int64_t>(kChunk) * n;
    engine.neighbours.box = structmd::Box<float>::make(liquid.length, liquid.length, liquid.length);
    engine.table = {ljTable, 1, nullptr};
    engine.out.force = reinterpret_cast<structmd::Real4<float>*>(scattered);
    auto evaluate_engine = [&] {
        cudaMemsetAsync(scattered, 0, sizeof(float4) * n);
        structmd::for_each_lone_lane_kernel<<<blocks, 128>>>(int64_t(n), 1, engine);
    };
    const Variant variants[] = {{"full", full.meanNeighbours, evaluate_full},
                                {"engine", full.meanNeighbours, evaluate_engine},
                                {"full-table", full.meanNeighbours, engine_like(full_forces_engine_like<true, false>, force)},
                                {"full-scatter", full.meanNeighbours, engine_like(full_forces_engine_like<false, true>, scattered)},
                                {"full-both", full.meanNeighbours, engine_like(full_forces_engine_like<true, true>, scattered)},
                                {"half-float", half.meanNeighbours, evaluate_half_float},
                                {"half-fixed", half.meanNeighbours, evaluate_half_fixed}};
    for (const Variant& v : variants) {
        v.evaluate();
        check(cudaDeviceSynchronize(), v.name);
        if (std::string(v.name) == "full-scatter" || std::string(v.name) == "full-both" || std::string(v.name) == "engine") {
            std::vector<float4> bySlot(n), byParticle(n);
            check(cudaMemcpy(byParticle.data(), scattered, sizeof(float4) * n, cudaMemcpyDeviceToHost), "copy");
            for (int k = 0; k < n; ++k) bySlot[k] = byParticle[shuffled[k]];
            check(cudaMemcpy(force, bySlot.data(), sizeof(float4) * n, cudaMemcpyHostToDevice), "copy");
        }
        const double error = max_difference(force, reference, n);
        const double us = time_us(v.evaluate, repeats);
        std::printf("%10d,%-6s,%-10s,%6.1f,%10.1f,%10.3e,%9.2e\n", n, morton ? "morton" : "rows", v.name, v.neighbours, us,
                    n / (us * 1e-6), error);
    }
    cudaFree(order);
    cudaFree(ljTable);
    cudaFree(engineList);
    cudaFree(table);
    cudaFree(scattered);
    time_builds(n, pos, liquid.length, cells, rank, start, full, morton);
    cudaFree(pos);
    cudaFree(rank);
    cudaFree(start);
    cudaFree(full.list);
    cudaFree(full.count);
    cudaFree(half.list);
    cudaFree(half.count);
    cudaFree(reference);
    cudaFree(force);
    cudaFree(fixedForce);
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<int> sizes;
    for (int a = 1; a < argc; ++a) sizes.push_back(std::atoi(argv[a]));
    if (sizes.empty()) sizes = {14, 25, 63, 100, 159};
    cudaDeviceProp prop{};
    check(cudaGetDeviceProperties(&prop, 0), "device");
    std::printf("# %s\n", prop.name);
    std::printf("%10s,%-6s,%-10s,%6s,%10s,%10s,%9s\n", "particles", "order", "variant", "list", "us", "evals*N/s",
                "max|dF|");
    for (int edge : sizes)
        for (bool morton : {false, true}) run(edge, morton);
    return 0;
}
