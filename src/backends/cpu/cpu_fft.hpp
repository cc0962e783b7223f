#pragma once
// The CPU backend's 3D FFT (core/fft_grid.hpp for the layout) on pocketfft, the header-only C++
// library (pocketfft_hdronly.h, found by CMake in .deps/include or the system's include path).
#include <complex>
#include <cstddef>

#include <pocketfft_hdronly.h>

#include "backends/cpu/cpu_backend.hpp"
#include "core/fft_grid.hpp"

namespace structmd {

template <class R>
class CpuFft3d {
public:
    CpuFft3d(const CpuBackend& backend, FftGrid grid, FftAxes axes = FftAxes::xyz)
        : threads_(static_cast<size_t>(backend.threads())),
          shape_{size_t(grid.nz), size_t(grid.ny), size_t(grid.nx)},
          realStrides_{ptrdiff_t(sizeof(R)) * grid.nx * grid.ny, ptrdiff_t(sizeof(R)) * grid.nx, ptrdiff_t(sizeof(R))},
          spectrumStrides_{ptrdiff_t(sizeof(Complex<R>)) * grid.half_x() * grid.ny,
                           ptrdiff_t(sizeof(Complex<R>)) * grid.half_x(), ptrdiff_t(sizeof(Complex<R>))},
          axes_(axes == FftAxes::xyz ? pocketfft::shape_t{0, 1, 2} : pocketfft::shape_t{1, 2}) {}

    void forward(const R* real, Complex<R>* spectrum) const {
        pocketfft::r2c(shape_, realStrides_, spectrumStrides_, axes_, pocketfft::FORWARD, real,
                       reinterpret_cast<std::complex<R>*>(spectrum), R(1), threads_);
    }
    void inverse(const Complex<R>* spectrum, R* real) const {
        pocketfft::c2r(shape_, spectrumStrides_, realStrides_, axes_, pocketfft::BACKWARD,
                       reinterpret_cast<const std::complex<R>*>(spectrum), real, R(1), threads_);
    }

private:
    size_t threads_;
    pocketfft::shape_t shape_;
    pocketfft::stride_t realStrides_, spectrumStrides_;
    pocketfft::shape_t axes_;  // the transformed ones; pocketfft batches over the others
};

}  // namespace structmd
