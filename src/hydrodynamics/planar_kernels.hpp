#pragma once
// The hydrodynamic kernels of particles that move in a plane (Pelaez et al., "Hydrodynamic
// fluctuations in quasi-two dimensional diffusion", J. Stat. Mech. 063207 (2018), eqs. 20-25): the
// Fourier transform of the in-plane mobility between two Gaussian blobs of width sigma at in-plane
// wave vector k (k = |k|, k^ = k / k, k^perp = k^ turned by 90 degrees),
//   M(k) = exp(-k^2 sigma^2) / eta  [ T(k) k^perp k^perp^T + L(k) k^ k^T ],
// of which the grid supplies exp(-k^2 sigma^2) (spreading and interpolating with the Gaussian) and
// these functors T and L, times eta.
//
// Quasi-2D: the particles lie in the plane z = 0 of an unbounded 3D Stokes fluid, their forces
// spread with a 3D Gaussian of sigma = a / sqrt(pi) (the force coupling method's, whose self
// mobility is 1 / (6 pi eta a)). Integrating the 3D Oseen kernel (I - K K^T / K^2) / K^2 over the
// out-of-plane wave number, K^2 = k^2 + k_z^2, with the Gaussians' exp(-K^2 sigma^2), gives
//   T(k) = erfc(k sigma) exp(k^2 sigma^2) / (2 k),
//   L(k) = [erfc(k sigma) exp(k^2 sigma^2) (1/2 + k^2 sigma^2) - k sigma / sqrt(pi)] / (2 k).
// L != 0: the in-plane flow is compressible, so the mobility has a divergence (thermal drift).
//
// True 2D: a 2D Stokes fluid (the plane is all there is), T(k) = 1 / k^2, L(k) = 0: incompressible,
// no drift. Its sigma = 0.66556976637 a is UAMMD's, which makes the periodic self mobility
// (ln(L / a) - 1.3105) / (4 pi eta) for large L.
#include "core/hd.hpp"

namespace structmd {

enum class PlanarHydrodynamics { quasi2D = 0, true2D = 1 };  // the order of the text option

template <class R>
struct PlanarKernel {
    PlanarHydrodynamics kind;
    R sigma;

    // T(k) and L(k) at |k| = k > 0.
    SMD_HD SMD_INLINE void operator()(R k, R& transverse, R& longitudinal) const {
        if (kind == PlanarHydrodynamics::true2D) {
            transverse = R(1) / (k * k);
            longitudinal = R(0);
            return;
        }
        const R ks = k * sigma;
        // erfc(x) exp(x^2) stays finite (< 1) in single precision too on every grid the plan allows
        // (spacing >= sigma / 1.65 before rounding up to a size the support fits in: k sigma < 9).
        const R scaledErfc = erfc(ks) * exp(ks * ks);
        const R inverseTwoK = R(0.5) / k;
        transverse = scaledErfc * inverseTwoK;
        longitudinal = (scaledErfc * (R(0.5) + ks * ks) - ks * R(0.5641895835477563)) * inverseTwoK;
    }

    SMD_HD SMD_INLINE bool compressible() const { return kind == PlanarHydrodynamics::quasi2D; }
};

}  // namespace structmd
