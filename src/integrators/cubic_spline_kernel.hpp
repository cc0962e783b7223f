#pragma once
// The M4 cubic spline of smoothed particle hydrodynamics (Monaghan 2005), in three dimensions, of
// smoothing length h and support 2h: with q = r / h,
//   W(r) = 1 / (pi h^3) * { 1 - 3/2 q^2 + 3/4 q^3   for q < 1
//                         { 1/4 (2 - q)^3           for 1 <= q < 2
//                         { 0                       beyond,
// normalised (its integral over space is 1) and twice continuously differentiable.
#include "core/hd.hpp"

namespace structmd {

template <class R>
struct CubicSplineKernel {
    R h;

    SMD_HD SMD_INLINE R support() const { return R(2) * h; }

    SMD_HD SMD_INLINE R value(R r) const {
        const R q = r / h;
        const R norm = R(1) / (R(3.14159265358979323846) * h * h * h);
        if (q < R(1)) return norm * (R(1) - R(1.5) * q * q + R(0.75) * q * q * q);
        if (q < R(2)) {
            const R t = R(2) - q;
            return norm * R(0.25) * t * t * t;
        }
        return R(0);
    }

    // dW/dr divided by r, finite at r = 0: the gradient of W(|r_i - r_j|) with respect to r_i is
    // this times r_i - r_j.
    SMD_HD SMD_INLINE R derivative_over_r(R r) const {
        const R q = r / h;
        const R norm = R(1) / (R(3.14159265358979323846) * h * h * h * h * h);
        if (q < R(1)) return norm * (R(-3) + R(2.25) * q);
        if (q < R(2)) {
            const R t = R(2) - q;
            return norm * R(-0.75) * t * t / q;
        }
        return R(0);
    }
};

}  // namespace structmd
