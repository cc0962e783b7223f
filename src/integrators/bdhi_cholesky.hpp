#pragma once
// ["BDHIOpenBoundary","Cholesky"]: the noise M^{1/2} W as L W, L the Cholesky factor of the dense
// 3N x 3N mobility (M = L L^T, factored every step by the backend: B::Cholesky). Exact, and O(N^3)
// per step: for small systems. L W has the covariance M that the noise needs, but it is not the
// symmetric square root that BdhiLanczos approximates: the two methods give the same statistics,
// not the same trajectory, from the same W.
#include <memory>

#include "integrators/bdhi_open_boundary.hpp"

namespace structmd {

// noise = L w, L lower triangular in the column-major matrix of leading dimension 3N; one particle's
// three rows per call.
template <class R>
struct LowerTriangularProduct {
    const R* factor;
    int64_t rows;
    const R* w;
    R* noise;
    SMD_HD void operator()(int64_t i) const {
        for (int64_t row = 3 * i; row < 3 * i + 3; ++row) {
            R sum = R(0);
            for (int64_t column = 0; column <= row; ++column) sum += factor[row + column * rows] * w[column];
            noise[row] = sum;
        }
    }
};

// The factorisation's outcome, kept in backend memory, becomes a fault of the step: the host hears
// of it at the end of the call, as of a blow-up.
struct ReportFailedFactorisation {
    const int* failed;
    FaultSlot fault;
    SMD_HD void operator()(int64_t) const {
        if (*failed != 0) fault.report(0, FaultQuantity::mobility);
    }
};

template <class B, class R>
class BdhiCholesky : public BdhiOpenBoundary<B, R> {
public:
    using BdhiOpenBoundary<B, R>::BdhiOpenBoundary;

protected:
    void mobility_sqrt(int64_t n, Particles<B, R>& p, const R* w, R* noise) override {
        const B& backend = this->backend();
        const int64_t rows = 3 * n;
        if (!cholesky_ || rows != rows_) {
            backend.resize(matrix_, static_cast<size_t>(rows * rows));
            backend.resize(failed_, 1);
            cholesky_ = std::make_unique<typename B::template Cholesky<R>>(backend, rows);
            rows_ = rows;
        }
        backend.for_each(n * n, FillDenseMobility<R>{this->spheres(), n, this->rpy(), matrix_.data()});
        cholesky_->factor(matrix_.data(), failed_.data());
        backend.for_each(1, ReportFailedFactorisation{failed_.data(), p.fault_slot(1)});
        backend.for_each(n, LowerTriangularProduct<R>{matrix_.data(), rows, w, noise});
    }

private:
    int64_t rows_ = 0;
    typename B::template Buffer<R> matrix_;
    typename B::template Buffer<int> failed_;
    std::unique_ptr<typename B::template Cholesky<R>> cholesky_;
};

}  // namespace structmd
