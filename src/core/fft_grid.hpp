#pragma once
// The layout of the 3D real-to-complex transforms every backend's Fft3d performs (backends/cpu/
// cpu_fft.hpp on pocketfft, backends/cuda/cuda_fft.cuh on cuFFT): a real grid of nx * ny * nz points,
// x fastest, and its half spectrum of (nx/2 + 1) * ny * nz complex numbers, x fastest. Neither
// direction is normalised: inverse(forward(g)) = nx ny nz g. A grid with nz = 1 is a 2D transform (the
// planar hydrodynamics). Long-range electrostatics and the spectral hydrodynamics use it. Made with
// FftAxes::xy, the transform is the 2D one of every z plane on its own, nz of them in one batched call
// (the doubly periodic slab's), with the same layout; then inverse(forward(g)) = nx ny g.
#include "core/hd.hpp"

#if SMD_HOST_CODE
#include <cstdint>  // NVRTC takes the fixed-width integers from core/hd.hpp
#endif

namespace structmd {

// Laid out as std::complex and cufft(Double)Complex, so a buffer of them is handed to either library;
// aligned to its size as cufftComplex (float2) is, so a number is one load, not two (the DPStokes z
// solve ran 10-14% faster for it on an H200, docs/benchmarks.md).
template <class R>
struct alignas(2 * sizeof(R)) Complex {
    R re, im;
};

// The axes a transform covers: all three, or x and y of each z plane.
enum class FftAxes : int { xyz, xy };

struct FftGrid {
    int nx = 0, ny = 0, nz = 0;

    SMD_HD SMD_INLINE int64_t points() const { return int64_t(nx) * ny * nz; }
    SMD_HD SMD_INLINE int half_x() const { return nx / 2 + 1; }
    SMD_HD SMD_INLINE int64_t spectrum_points() const { return int64_t(half_x()) * ny * nz; }
    SMD_HD SMD_INLINE int64_t index(int x, int y, int z) const { return x + int64_t(nx) * (y + int64_t(ny) * z); }
};

}  // namespace structmd
