#pragma once
// The wave-space (far-field) part of the positively split Ewald sum of the RPY mobility (Fiore,
// Balboa Usabiaga, Donev & Swan, J. Chem. Phys. 146, 124116 (2017), eq. 9):
//   M_far(r) = 1/V sum_{k != 0} (sin(k a) / (k a))^2 (1 + k^2 / (4 xi^2)) exp(-k^2 / (4 xi^2)) / (eta k^2)
//              (I - k^ k^) exp(i k.r),
// computed on the force coupling mesh (fcm_mesh.hpp) as a spectral Ewald sum (Lindbo & Tornberg,
// J. Comput. Phys. 230, 8744 (2011)): forces spread with a Gaussian of width sigma, the multiplier
// divided by the two Gaussians' transforms exp(-k^2 sigma^2), and the velocity averaged back with the
// same Gaussian. The noise M_far^{1/2} W is drawn on the same wave vectors in the same pass, as the
// force coupling method does.
//
// Grid and kernel as UAMMD's BDHI::PSE chooses them: the wave numbers up to k_c = 2 xi sqrt(-ln tol)
// (where the multiplier's exp(-k^2/(4 xi^2)) reaches tol) are resolved, n = 2 L k_c / (2 pi) + 1 points
// (rounded up to an FFT-friendly size); the Gaussian is truncated at m standard deviations with
// erfc(m / sqrt 2) = tol / 10, on the P = support / 2 nearest points each side, support odd from
// m = 0.976 sqrt(pi support) (Lindbo & Tornberg's sec. 4.1), and sigma = (support h / 2) / m. Unlike
// UAMMD, h is the coarsest of the three spacings (UAMMD: the finest), and the support grows to cover
// m sigma along the finest axis: on a grid whose spacings differ (box sides rounded to FFT sizes
// differently) UAMMD's Gaussian is under-resolved along the coarser axes (3e-5 mu0 of error in the
// self-mobility at tol 1e-5, psi 0.8, box 13 x 14 x 15; 4e-6 with this choice).
#include <algorithm>
#include <cmath>
#include <string>

#include "core/vec.hpp"
#include "hydrodynamics/fcm_mesh.hpp"

namespace structmd {

// G(k) = (sin(k a) / (k a))^2 (1 + k^2 / (4 xi^2)) exp(k^2 sigma^2 - k^2 / (4 xi^2)) / (eta k^2).
template <class R>
struct PseFarGreen {
    R inverseViscosity;
    R radius;
    R inverseFourXi2;  // 1 / (4 xi^2)
    R kernelWidth2;    // sigma^2: exp(k^2 sigma^2) undoes the spreading and the averaging
    SMD_HD SMD_INLINE R operator()(R k2) const {
        const R ka = sqrt(k2) * radius;
        const R sinc = sin(ka) / ka;
        return inverseViscosity * sinc * sinc * (R(1) + k2 * inverseFourXi2) * exp(k2 * (kernelWidth2 - inverseFourXi2)) / k2;
    }
};

#if SMD_HOST_CODE
inline FcmPlan make_pse_far_plan(const double box[3], double xi, double tolerance, const std::string& path) {
    FcmPlan plan;
    const double cutoffWave = 2.0 * xi * std::sqrt(-std::log(tolerance));
    // The shortest wavelength the far field needs: the grid spacing is at most half of it.
    const double cutoffWavelength = 2.0 * M_PI / cutoffWave;
    double wanted[3];
    for (int d = 0; d < 3; ++d) {
        plan.box[d] = box[d];
        if (!std::isfinite(box[d]) || !(box[d] > 0.0))
            throw Error(STRUCTMD_ERR_UNSUPPORTED, path + ": the positively split Ewald method needs a periodic box "
                                                         "along x, y and z, but the box is not periodic along " +
                                                         std::string(1, "xyz"[d]));
        wanted[d] = std::floor(2.0 * box[d] / cutoffWavelength) + 1.0;
    }
    int sizes[3];
    checked_grid_sizes(wanted, 3, sizes, path + ".parameters.psi", "psi is too large for the box at this tolerance");
    plan.grid = FftGrid{sizes[0], sizes[1], sizes[2]};
    double deviations = 1.0;
    while (std::erfc(deviations / std::sqrt(2.0)) > 0.1 * tolerance) deviations += 0.01;
    const double shape = 0.976;  // Lindbo & Tornberg's m = C sqrt(pi P), C = 0.976
    plan.support = static_cast<int>(std::pow(deviations / shape, 2) / M_PI + 0.5) + 1;
    if (plan.support % 2 == 0) {
        ++plan.support;
        deviations = shape * std::sqrt(M_PI * (plan.support - 1.5));
    }
    // The width from the coarsest spacing, so that every axis resolves the Gaussian as finely as
    // UAMMD's choice does on a cubic grid; the finer axes then need more points to reach m sigma.
    double coarsest = box[0] / sizes[0], finest = coarsest;
    for (int d = 1; d < 3; ++d) {
        coarsest = std::max(coarsest, box[d] / sizes[d]);
        finest = std::min(finest, box[d] / sizes[d]);
    }
    plan.sigma = 0.5 * plan.support * coarsest / deviations;
    plan.support = static_cast<int>(std::ceil(plan.support * coarsest / finest - 1e-9));
    plan.support += 1 - plan.support % 2;
    return plan;
}
#endif

}  // namespace structmd
