#pragma once
// Peskin's 3-point kernel (Roma, Peskin & Berger, J. Comput. Phys. 153, 509 (1999)), the immersed
// boundary method's smeared delta along one axis, in grid units r = distance / h:
//   phi(r) = (1 + sqrt(1 - 3 r^2)) / 3                     |r| <= 1/2
//          = (5 - 3 |r| - sqrt(1 - 3 (1 - |r|)^2)) / 6       1/2 <= |r| <= 3/2
//          = 0                                             otherwise,
// whose weights on any three consecutive nodes sum to 1 with first moment 0 and squares summing to
// 1/2 wherever the particle is. A particle spread with it onto a staggered Stokes grid moves as a
// sphere of hydrodynamic radius about 0.91 h (Balboa Usabiaga et al., Multiscale Model. Simul. 10,
// 1369 (2012)), to about 1 % depending on where in the cell it is.
#include "core/hd.hpp"

namespace structmd {

// The nodes one particle's kernel can reach on the centres and on the faces half a cell away: 3 of
// each, 4 together.
inline constexpr int kPeskinWindow = 4;
// The hydrodynamic radius over the grid spacing (UAMMD's BDHI::FIB uses the same figure).
inline constexpr double kPeskin3RadiusOverSpacing = 0.91;

template <class R>
SMD_HD SMD_INLINE R peskin3(R r) {
    const R a = r < R(0) ? -r : r;
    if (a <= R(0.5)) return (R(1) + sqrt(R(1) - R(3) * a * a)) / R(3);
    if (a < R(1.5)) {
        const R b = R(1) - a;
        return (R(5) - R(3) * a - sqrt(R(1) - R(3) * b * b)) / R(6);
    }
    return R(0);
}

}  // namespace structmd
