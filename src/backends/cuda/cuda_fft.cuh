#pragma once
// The CUDA backend's 3D FFT (core/fft_grid.hpp for the layout) on cuFFT. A transform is work the
// host launches itself: it runs on the engine's stream after what the step graphs recorded before
// it, and before what they record after it.
#include <cufft.h>

#include <string>
#include <type_traits>

#include "backends/cuda/cuda_backend.cuh"
#include "core/error.hpp"
#include "core/fft_grid.hpp"

namespace structmd {

inline void cufft_check(cufftResult status, const char* what) {
    if (status == CUFFT_SUCCESS) return;
    throw Error(status == CUFFT_ALLOC_FAILED ? STRUCTMD_ERR_MEMORY : STRUCTMD_ERR_DEVICE,
                std::string(what) + ": cuFFT error " + std::to_string(static_cast<int>(status)));
}

template <class R>
class CudaFft3d {
    static constexpr bool kDouble = std::is_same<R, double>::value;

public:
    CudaFft3d(const CudaBackend& backend, FftGrid grid, FftAxes axes = FftAxes::xyz) : backend_(backend) {
        // cuFFT's dimensions go slowest first; a grid one point thick is planned as the 2D transform it is.
        const cufftType forward = kDouble ? CUFFT_D2Z : CUFFT_R2C, inverse = kDouble ? CUFFT_Z2D : CUFFT_C2R;
        if (axes == FftAxes::xy) {
            // nz 2D transforms in one batch, planes packed one after the other in either layout.
            int sizes[2] = {grid.ny, grid.nx}, real[2] = {grid.ny, grid.nx}, spectrum[2] = {grid.ny, grid.half_x()};
            const int realPlane = grid.nx * grid.ny, spectrumPlane = grid.half_x() * grid.ny;
            cufft_check(cufftPlanMany(&forward_, 2, sizes, real, 1, realPlane, spectrum, 1, spectrumPlane, forward,
                                      grid.nz),
                        "planning a batch of forward FFTs");
            cufft_check(cufftPlanMany(&inverse_, 2, sizes, spectrum, 1, spectrumPlane, real, 1, realPlane, inverse,
                                      grid.nz),
                        "planning a batch of inverse FFTs");
        } else if (grid.nz == 1) {
            cufft_check(cufftPlan2d(&forward_, grid.ny, grid.nx, forward), "planning a forward FFT");
            cufft_check(cufftPlan2d(&inverse_, grid.ny, grid.nx, inverse), "planning an inverse FFT");
        } else {
            cufft_check(cufftPlan3d(&forward_, grid.nz, grid.ny, grid.nx, forward), "planning a forward FFT");
            cufft_check(cufftPlan3d(&inverse_, grid.nz, grid.ny, grid.nx, inverse), "planning an inverse FFT");
        }
    }
    CudaFft3d(const CudaFft3d&) = delete;
    CudaFft3d& operator=(const CudaFft3d&) = delete;
    ~CudaFft3d() {
        cufftDestroy(forward_);
        cufftDestroy(inverse_);
    }

    void forward(const R* real, Complex<R>* spectrum) const {
        cufft_check(cufftSetStream(forward_, stream()), "choosing the FFT stream");
        if constexpr (kDouble)
            cufft_check(cufftExecD2Z(forward_, const_cast<double*>(real), reinterpret_cast<cufftDoubleComplex*>(spectrum)),
                        "running a forward FFT");
        else
            cufft_check(cufftExecR2C(forward_, const_cast<float*>(real), reinterpret_cast<cufftComplex*>(spectrum)),
                        "running a forward FFT");
    }
    void inverse(const Complex<R>* spectrum, R* real) const {
        cufft_check(cufftSetStream(inverse_, stream()), "choosing the FFT stream");
        // cuFFT may overwrite the input of a complex-to-real transform: the spectrum is not read again.
        if constexpr (kDouble)
            cufft_check(cufftExecZ2D(inverse_, reinterpret_cast<cufftDoubleComplex*>(const_cast<Complex<R>*>(spectrum)),
                                     real),
                        "running an inverse FFT");
        else
            cufft_check(cufftExecC2R(inverse_, reinterpret_cast<cufftComplex*>(const_cast<Complex<R>*>(spectrum)), real),
                        "running an inverse FFT");
    }

private:
    cudaStream_t stream() const { return static_cast<cudaStream_t>(backend_.host_launch_stream()); }

    const CudaBackend& backend_;
    cufftHandle forward_ = 0, inverse_ = 0;
};

}  // namespace structmd
