#pragma once
// The CPU backend with the parts its engines' units need (FFT, dense Cholesky).
#include "backends/cpu/cpu_backend.hpp"
#include "backends/cpu/cpu_cholesky.hpp"
#include "backends/cpu/cpu_fft.hpp"
