#pragma once
// Peskin's three-point kernel (Roma, Peskin & Berger, J. Comput. Phys. 153, 509 (1999)), the
// regularised delta of the immersed boundary method in units of the grid spacing h: delta_h(x) =
// phi(x/h) phi(y/h) phi(z/h) / h^3, with
//   phi(r) = (1 + sqrt(1 - 3 r^2)) / 3                        |r| <= 1/2
//   phi(r) = (5 - 3 |r| - sqrt(1 - 3 (1 - |r|)^2)) / 6         1/2 <= |r| <= 3/2
//   phi(r) = 0                                                 otherwise.
// It sums to 1 over the grid points (sum_j phi(r - j) = 1, so spreading conserves momentum) and its
// first moment vanishes; sum_j phi(r - j)^2 = 1/2 exactly, wherever the particle stands.
#include <cmath>

#include "core/hd.hpp"

namespace structmd {

template <class R>
SMD_HD SMD_INLINE R peskin_three_point(R r) {
    const R a = fabs(r);
    if (a <= R(0.5)) return (R(1) + sqrt(R(1) - R(3) * a * a)) / R(3);
    if (a < R(1.5)) {
        const R b = R(1) - a;
        return (R(5) - R(3) * a - sqrt(fmax(R(1) - R(3) * b * b, R(0)))) / R(6);
    }
    return R(0);
}

}  // namespace structmd
