#pragma once
// The CPU backend's dense Cholesky factorisation, on Eigen's LLT (header-only, found by CMake in
// .deps/include/eigen3 or the system's include path): a kept library rather than a loop of our own,
// and no LAPACK to link on machines that lack it.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cstdint>

#include "backends/cpu/cpu_backend.hpp"

namespace structmd {

template <class R>
class CpuCholesky {
public:
    CpuCholesky(const CpuBackend&, int64_t size) : size_(size) {}

    // Overwrites the lower triangle of the symmetric positive-definite size x size matrix
    // (column-major, its lower triangle read) with its Cholesky factor L, M = L L^T; the strictly upper
    // triangle is left unspecified. *failed, in backend memory, becomes 1 where the matrix is not
    // positive definite (L is then unusable), 0 otherwise.
    void factor(R* matrix, int* failed) const {
        using Matrix = Eigen::Matrix<R, Eigen::Dynamic, Eigen::Dynamic>;
        Eigen::Map<Matrix> whole(matrix, size_, size_);
        Eigen::LLT<Eigen::Ref<Matrix>, Eigen::Lower> llt(whole);
        *failed = llt.info() == Eigen::Success ? 0 : 1;
    }

private:
    int64_t size_;
};

}  // namespace structmd
