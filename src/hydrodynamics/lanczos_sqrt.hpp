#pragma once
// y = A^{1/2} z for a symmetric positive-definite operator A known only through its product with a
// vector (Ando, Chow, Saad & Skolnick, J. Chem. Phys. 137, 064106, 2012): after k Lanczos steps,
// A V_k = V_k T_k + beta_k v_{k+1} e_k^T with V_k orthonormal and T_k tridiagonal, and
//   y_k = |z| V_k T_k^{1/2} e_1.
// The iteration stops when |y_k - y_{k-1}| <= tolerance |y_k|; since V_k is orthonormal, that is
// |s_k - (s_{k-1}, 0)| <= tolerance |s_k| with s_k = T_k^{1/2} e_1, which the host computes from T_k
// alone (m x m, m ~ tens: tridiagonal_sqrt.hpp).
// Host reads: |z|^2 once, then one reduction per iteration (v.w, w.w and v.v in one sum), from which
// the host forms T's next diagonal and off-diagonal entries and tests convergence. Nothing else
// leaves the backend.
// Generic over the operator: the open-boundary RPY mobility uses it, and any other positive-definite
// product (a near-field mobility) may.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/vec.hpp"
#include "hydrodynamics/tridiagonal_sqrt.hpp"

namespace structmd {

template <class R>
struct LanczosSquaredNorm {
    const R* x;
    SMD_HD double operator()(int64_t i) const { return static_cast<double>(x[i]) * static_cast<double>(x[i]); }
};

// (v.w, w.w, v.v), summed in double.
template <class R>
struct LanczosProjections {
    const R* w;
    const R* v;
    SMD_HD Vec3<double> operator()(int64_t i) const {
        const double wi = static_cast<double>(w[i]), vi = static_cast<double>(v[i]);
        return {vi * wi, wi * wi, vi * vi};
    }
};

// y = c x
template <class R>
struct LanczosScale {
    const R* x;
    R* y;
    R c;
    SMD_HD void operator()(int64_t i) const { y[i] = c * x[i]; }
};

// y += c x
template <class R>
struct LanczosAddScaled {
    const R* x;
    R* y;
    R c;
    SMD_HD void operator()(int64_t i) const { y[i] += c * x[i]; }
};

// next = (w - alpha v) / beta
template <class R>
struct LanczosNext {
    const R* w;
    const R* v;
    R* next;
    R alpha, inverseBeta;
    SMD_HD void operator()(int64_t i) const { next[i] = (w[i] - alpha * v[i]) * inverseBeta; }
};

template <class B, class R>
class LanczosSqrt {
public:
    // what: the operator, as error messages name it.
    LanczosSqrt(const B& backend, double tolerance, int maxIterations, std::string what)
        : backend_(backend), tolerance_(tolerance), maxIterations_(maxIterations), what_(std::move(what)) {}

    // out = A^{1/2} z, for z and out arrays of n numbers in backend memory (distinct); apply(v, Av)
    // writes A v for a backend array v of n numbers. Returns the number of iterations it took.
    template <class Apply>
    int apply_sqrt(int64_t n, const R* z, R* out, const Apply& apply) {
        const double zNorm = std::sqrt(backend_.template reduce<double>(n, LanczosSquaredNorm<R>{z}, 0.0));
        if (!(zNorm > 0.0)) {
            backend_.for_each(n, LanczosScale<R>{z, out, R(0)});
            return 0;
        }
        backend_.resize(w_, static_cast<size_t>(n));
        basis_vector(0, n);
        backend_.for_each(n, LanczosScale<R>{z, basis_[0].data(), R(1.0 / zNorm)});
        diagonal_.clear();
        offDiagonal_.clear();
        // Below this, beta^2 (a difference of sums) is rounding: the Krylov space is exhausted.
        const double exhausted = 64.0 * std::numeric_limits<R>::epsilon();
        for (int k = 0; k < maxIterations_; ++k) {
            R* v = basis_[k].data();
            apply(static_cast<const R*>(v), w_.data());
            if (k > 0) backend_.for_each(n, LanczosAddScaled<R>{basis_[k - 1].data(), w_.data(), R(-offDiagonal_[k - 1])});
            const Vec3<double> p = backend_.template reduce<Vec3<double>>(n, LanczosProjections<R>{w_.data(), v}, {0, 0, 0});
            const double alpha = p.x / p.z;
            const double beta2 = p.y - p.x * p.x / p.z;
            diagonal_.push_back(alpha);
            if (!tridiagonal_sqrt_first_column(diagonal_, offDiagonal_, s_))
                throw Error(STRUCTMD_ERR_NUMERICAL, what_ + " is not positive definite (its Lanczos tridiagonal has an "
                                                            "eigenvalue <= 0)");
            const bool converged = k > 0 && relative_change() <= tolerance_;
            if (converged || beta2 <= exhausted * p.y || k + 1 == n) {
                combine(n, zNorm, out);
                return k + 1;
            }
            sPrevious_ = s_;
            const double beta = std::sqrt(beta2);
            offDiagonal_.push_back(beta);
            basis_vector(k + 1, n);
            backend_.for_each(n, LanczosNext<R>{w_.data(), v, basis_[k + 1].data(), R(alpha), R(1.0 / beta)});
        }
        throw Error(STRUCTMD_ERR_NUMERICAL, what_ + ": the Lanczos square root did not reach the tolerance " +
                                                std::to_string(tolerance_) + " in " + std::to_string(maxIterations_) +
                                                " iterations");
    }

private:
    // |s_k - (s_{k-1}, 0)| / |s_k|
    double relative_change() const {
        double difference = 0.0, norm = 0.0;
        for (size_t i = 0; i < s_.size(); ++i) {
            const double d = s_[i] - (i < sPrevious_.size() ? sPrevious_[i] : 0.0);
            difference += d * d;
            norm += s_[i] * s_[i];
        }
        return std::sqrt(difference / norm);
    }

    // out = |z| sum_i s_i v_i
    void combine(int64_t n, double zNorm, R* out) const {
        backend_.for_each(n, LanczosScale<R>{basis_[0].data(), out, R(zNorm * s_[0])});
        for (size_t i = 1; i < s_.size(); ++i)
            backend_.for_each(n, LanczosAddScaled<R>{basis_[i].data(), out, R(zNorm * s_[i])});
    }

    // The basis grows as iterations need it and is kept for the next call.
    void basis_vector(int k, int64_t n) {
        while (static_cast<int>(basis_.size()) <= k) basis_.emplace_back();
        backend_.resize(basis_[k], static_cast<size_t>(n));
    }

    const B& backend_;
    double tolerance_;
    int maxIterations_;
    std::string what_;
    std::vector<typename B::template Buffer<R>> basis_;
    typename B::template Buffer<R> w_;
    std::vector<double> diagonal_, offDiagonal_, s_, sPrevious_;
};

}  // namespace structmd
