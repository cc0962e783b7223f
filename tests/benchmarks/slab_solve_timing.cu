// nvcc -O3 -std=c++17 -arch=sm_90 --expt-relaxed-constexpr -Isrc -Iinclude -o slab_solve_timing tests/benchmarks/slab_solve_timing.cu
//
// The DPStokes z solve (hydrodynamics/slab_stokes.hpp, SlabStokesSolve) alone: half of a DPStokes
// step on an H200 (docs/benchmarks.md). Built against a source tree's headers, so that two trees'
// solves are timed side by side from one machine without building either library:
//   nvcc ... -I<tree>/src -I<tree>/include -o solve_<tree> tests/benchmarks/slab_solve_timing.cu
// It fills the band-limited kernel table and a random force spectrum on the device, then launches
// the solve as the CUDA backend does (a warp of lanes per wave vector, 128 threads a block) and
// prints microseconds per launch (cudaEvent, after warm-up) and a checksum of the velocity
// spectrum (the sum of |re| + |im| in double), equal between trees whose solves agree.
// Defaults: hydrodynamics_benchmark.py's grid at 1,000 spheres (150 x 150 x 30, slit walls).
// Usage: slab_solve_timing [--nx N] [--ny N] [--nz N] [--precision single|double] [--launches N]
#include <cuda_runtime.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "backends/cuda/launch_kernels.cuh"
#include "hydrodynamics/slab_stokes.hpp"
#include "standalone_cuda.cuh"

namespace {

using standalone::check;

template <class R>
void run(structmd::FftGrid grid, int launches) {
    using namespace structmd;
    // The benchmark's slit: spacing 0.5 in the plane, walls (nz - 1) 0.5 apart, viscosity 1.
    const double spacing = 0.5, lengthX = grid.nx * spacing, lengthY = grid.ny * spacing;
    const int64_t waves = int64_t(grid.half_x()) * grid.ny, spectrum = 3 * waves * grid.nz;
    // 32 bytes an entry in every tree; its type is the tree's (four doubles, or SlabKernelEntry).
    decltype(SlabKernelTable::table) table = nullptr;
    Complex<R>*force = nullptr, *velocity = nullptr;
    check(cudaMalloc(reinterpret_cast<void**>(&table), 32 * waves * grid.nz), "table");
    check(cudaMalloc(&force, sizeof(Complex<R>) * spectrum), "force");
    check(cudaMalloc(&velocity, sizeof(Complex<R>) * spectrum), "velocity");
    const int64_t entries = waves * grid.nz;
    for_each_kernel<<<unsigned((entries + 127) / 128), 128>>>(
        entries, SlabKernelTable{grid, lengthX, lengthY, spacing, table});
    std::vector<Complex<R>> host(spectrum);
    std::mt19937 engine(7);
    std::normal_distribution<double> normal;
    for (auto& f : host) f = {R(normal(engine)), R(normal(engine))};
    check(cudaMemcpy(force, host.data(), sizeof(Complex<R>) * spectrum, cudaMemcpyHostToDevice), "upload");

    const int lanes = 32;
    const SlabStokesSolve<R> solve{force, velocity, table, grid, lengthX, lengthY, spacing,
                                   spacing / (double(grid.nx) * grid.ny), SlabWalls::slit};
    const unsigned blocks = unsigned((waves * lanes + 127) / 128);
    for (int k = 0; k < 10; ++k) for_each_lanes_kernel<<<blocks, 128>>>(waves, lanes, solve);
    check(cudaDeviceSynchronize(), "warm-up");
    cudaEvent_t start, stop;
    cudaEventCreate(&start);
    cudaEventCreate(&stop);
    cudaEventRecord(start);
    for (int k = 0; k < launches; ++k) for_each_lanes_kernel<<<blocks, 128>>>(waves, lanes, solve);
    cudaEventRecord(stop);
    check(cudaEventSynchronize(stop), "timed launches");
    float ms = 0.0f;
    cudaEventElapsedTime(&ms, start, stop);

    check(cudaMemcpy(host.data(), velocity, sizeof(Complex<R>) * spectrum, cudaMemcpyDeviceToHost), "download");
    double checksum = 0.0;
    for (const auto& u : host) checksum += std::fabs(double(u.re)) + std::fabs(double(u.im));
    std::printf("%d x %d x %d, %s: %.1f us a solve (%d launches), checksum %.17g\n", grid.nx, grid.ny, grid.nz,
                sizeof(R) == 4 ? "single" : "double", 1e3 * ms / launches, launches, checksum);
    cudaFree(table);
    cudaFree(force);
    cudaFree(velocity);
}

}  // namespace

int main(int argc, char** argv) {
    structmd::FftGrid grid{150, 150, 30};
    bool single = true;
    int launches = 200;
    for (int a = 1; a + 1 < argc; a += 2) {
        const char* value = argv[a + 1];
        if (!std::strcmp(argv[a], "--nx"))
            grid.nx = std::atoi(value);
        else if (!std::strcmp(argv[a], "--ny"))
            grid.ny = std::atoi(value);
        else if (!std::strcmp(argv[a], "--nz"))
            grid.nz = std::atoi(value);
        else if (!std::strcmp(argv[a], "--launches"))
            launches = std::atoi(value);
        else if (!std::strcmp(argv[a], "--precision"))
            single = !std::strcmp(value, "single");
        else {
            std::fprintf(stderr, "unknown option %s\n", argv[a]);
            return 2;
        }
    }
    if (single)
        run<float>(grid, launches);
    else
        run<double>(grid, launches);
    return 0;
}
