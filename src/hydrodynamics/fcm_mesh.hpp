#pragma once
// The force coupling method (Maxey & Patel, Int. J. Multiphase Flow 27, 1603 (2001); Keaveny,
// J. Comput. Phys. 269, 61 (2014)) in a triply periodic box: the displacement of every particle in
// one step of Brownian dynamics with hydrodynamic interactions,
//   dx = dt M F + sqrt(2 kT dt) M^{1/2} W,    M = J L^{-1} S,
// S spreading each force with the Gaussian g(r) = (2 pi sigma^2)^{-3/2} exp(-r^2 / (2 sigma^2)),
// sigma = a / sqrt(pi) (a the hydrodynamic radius), L^{-1} the Stokes solve in Fourier space,
//   u_k = (I - k k^T / k^2) f_k / (eta k^2),   k = 0 removed (no net flow),
// and J = S^T the same Gaussian's average of the velocity at the particle. The noise is a random
// velocity field drawn in Fourier space with covariance 2 kT dt times that of L^{-1} (Keaveny 2014,
// section 3), added to the deterministic one before the inverse transform: averaged by J it has
// covariance 2 kT dt M exactly, for the same grid and kernel as the deterministic part.
//
// The Nyquist planes of the grid are left out of both parts: the projector there has no consistent
// sign, and leaving them out keeps M symmetric and the noise its exact square root.
//
// The spreading and the average are gaussian_spreading.hpp's, periodic along z.
//
// The mesh is generic over the Gaussian's width and the Fourier multiplier G(k) that turns the force
// density into velocity (u_k = G(k) P_k f_k): FcmGreen below is the Stokes solve of the force
// coupling method; the positively split Ewald method's far field (pse_far_field.hpp) uses the same
// spreading, transform, noise and interpolation with its own G and kernel width.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "core/fft_grid.hpp"
#include "core/hd.hpp"
#include "core/random.hpp"
#include "core/vec.hpp"
#include "hydrodynamics/gaussian_spreading.hpp"
#include "neighbour/line_bins.hpp"
#include "state/particles.hpp"
#include "state/step_clock.hpp"

namespace structmd {

// Everything the mesh needs, fixed for one box (make_fcm_plan, make_pse_far_plan).
struct FcmPlan {
    FftGrid grid;
    double box[3] = {0, 0, 0};
    double sigma = 0.0;  // the Gaussian's width (the force coupling method's: a / sqrt(pi))
    int support = 0;     // grid points the Gaussian covers along each axis
};

template <class R>
using FcmAxes = GaussianAxes<R, FcmAxis<R>>;

#if SMD_HOST_CODE
template <class R>
inline FcmAxes<R> fcm_axes(const FcmPlan& plan) {
    const int sizes[3] = {plan.grid.nx, plan.grid.ny, plan.grid.nz};
    FcmAxis<R> axis[3];
    for (int d = 0; d < 3; ++d)
        axis[d] = FcmAxis<R>{R(plan.box[d] / sizes[d]), R(1.0 / plan.box[d]), sizes[d], plan.support,
                             R(0.5 / (plan.sigma * plan.sigma)), R(1.0 / std::sqrt(2.0 * M_PI * plan.sigma * plan.sigma))};
    return {axis[0], axis[1], axis[2], plan.grid};
}
#endif

// The Stokes solve of the force coupling method: G(k) = 1 / (eta k^2).
template <class R>
struct FcmGreen {
    R inverseViscosity;
    SMD_HD SMD_INLINE R operator()(R k2) const { return inverseViscosity / k2; }
};

// One wave vector of the half spectrum: the transformed force density (three components, one
// spectrum after the other) becomes the displacement field's spectrum,
//   A_k = dt/N G(k) P_k F_k  +  sqrt(2 kT dt G(k) / V) P_k Z_k,
// N the grid's points, V the box's volume, P_k = I - k k^T / k^2, Z_k complex normal with
// <Z Z^H> = I. The inverse transform (unnormalised) then gives dt u + noise on the grid. On the
// plane x = 0 the spectrum holds both k and -k: the one of higher index takes the conjugate of its
// partner's noise, so that the field is real.
template <class R, class Green>
struct FcmStokesSolve {
    Complex<R>* spectrum;
    FftGrid grid;
    Vec3<R> length;
    Green green;
    R driftScale;  // dt / N
    R noiseScale;  // 2 kT dt / V; 0: no noise
    uint64_t seed, noiseStream;
    ClockView now;  // the step keys the noise

    SMD_HD void operator()(int64_t at) const {
        const int hx = grid.half_x();
        const int64_t spectrumPoints = grid.spectrum_points();
        Complex<R>* fx = spectrum + at;
        Complex<R>* fy = fx + spectrumPoints;
        Complex<R>* fz = fy + spectrumPoints;
        const int x = static_cast<int>(at % hx);
        const int y = static_cast<int>((at / hx) % grid.ny);
        const int z = static_cast<int>(at / (int64_t(hx) * grid.ny));
        if (at == 0 || 2 * x == grid.nx || 2 * y == grid.ny || 2 * z == grid.nz) {
            *fx = *fy = *fz = Complex<R>{R(0), R(0)};
            return;
        }
        const R twoPi = R(6.283185307179586);
        const Vec3<R> k{twoPi * R(x) / length.x, twoPi * R(2 * y < grid.ny ? y : y - grid.ny) / length.y,
                        twoPi * R(2 * z < grid.nz ? z : z - grid.nz) / length.z};
        const R k2 = dot(k, k);
        const R g = green(k2);
        Vec3<R> re{fx->re, fy->re, fz->re}, im{fx->im, fy->im, fz->im};
        re = (driftScale * g) * re;
        im = (driftScale * g) * im;
        if (noiseScale > R(0)) {
            int64_t drawn = at;
            R conjugate = R(1);
            if (x == 0) {
                const int64_t partner = int64_t(hx) * ((grid.ny - y) % grid.ny + int64_t(grid.ny) * ((grid.nz - z) % grid.nz));
                if (partner < at) {
                    drawn = partner;
                    conjugate = R(-1);
                }
            }
            double xi[8];
            normal4(seed, noiseStream ^ static_cast<uint64_t>(2 * drawn), static_cast<uint64_t>(now.step()), xi);
            normal4(seed, noiseStream ^ static_cast<uint64_t>(2 * drawn + 1), static_cast<uint64_t>(now.step()), xi + 4);
            const R amplitude = sqrt(noiseScale * g * R(0.5));  // re and im each carry half
            re = re + amplitude * Vec3<R>{R(xi[0]), R(xi[1]), R(xi[2])};
            im = im + (conjugate * amplitude) * Vec3<R>{R(xi[4]), R(xi[5]), R(xi[6])};
        }
        re = re - (dot(k, re) / k2) * k;
        im = im - (dot(k, im) / k2) * k;
        *fx = Complex<R>{re.x, im.x};
        *fy = Complex<R>{re.y, im.y};
        *fz = Complex<R>{re.z, im.z};
    }
};

#if SMD_HOST_CODE
// The smallest size >= n whose only prime factors are 2, 3 and 5, and even (FFT-friendly).
inline int fft_friendly_size(int n) {
    for (int m = std::max(n, 2);; ++m) {
        if (m % 2) continue;
        int rest = m;
        for (int p : {2, 3, 5})
            while (rest % p == 0) rest /= p;
        if (rest == 1) return m;
    }
}

// The most points a spectral method's grid may have: 2^30, some 25 GB for its fields in single
// precision. Only a radius far below the box's scale (or a splitting parameter far above it) asks for
// more, and the counts would soon overflow an int (a radius of 1e-7 stopped the process at the first
// step with SIGFPE).
inline constexpr double kMaxGridPoints = 1073741824.0;

// The FFT-friendly points along each of the first `axes` axes for the counts wanted (not yet
// rounded), refused as INPUT at `parameter` when the grid would have more than kMaxGridPoints.
inline void checked_grid_sizes(const double* wanted, int axes, int* sizes, const std::string& parameter,
                               const std::string& cause) {
    double total = 1.0;
    std::string shape;
    for (int d = 0; d < axes; ++d) {
        total *= std::max(wanted[d], 2.0);
        shape += (d ? " x " : "") + std::to_string(static_cast<long long>(std::min(wanted[d], 1e18)));
    }
    if (!(total <= kMaxGridPoints))
        throw input_error(parameter, "the grid would need " + shape + " points, more than 2^30: " + cause);
    for (int d = 0; d < axes; ++d) sizes[d] = fft_friendly_size(static_cast<int>(wanted[d]));
}

// The grid and the kernel's support for a hydrodynamic radius and tolerance, as UAMMD's
// BDHI::FCM chooses them: the grid spacing h = sigma / f(tol), f growing from 0.55 to 1.65 as the
// tolerance falls (its empirical "upsampling"); the support covers the distance at which the
// Gaussian falls to tol of its peak. Unlike UAMMD, the grid is rounded up (finer) rather than
// down, and the radius stays the one given rather than being refitted to the rounded grid.
// resolvedSigma > 0: the grid is made fine enough for a narrower Gaussian of that width as well (the
// torques' of fcm_rotation.hpp).
inline FcmPlan make_fcm_plan(const double box[3], double radius, double tolerance, const std::string& path,
                             double resolvedSigma = 0.0) {
    FcmPlan plan;
    plan.sigma = radius / std::sqrt(M_PI);
    const double upsampling = std::min(0.55 + (-std::log10(3.0 * tolerance) / 10.0) * (1.65 - 0.55), 1.65);
    const double spacing = (resolvedSigma > 0.0 ? std::min(plan.sigma, resolvedSigma) : plan.sigma) / upsampling;
    const double reach = plan.sigma * std::sqrt(2.0 * std::log(1.0 / tolerance));
    double wanted[3];
    for (int d = 0; d < 3; ++d) {
        plan.box[d] = box[d];
        if (!std::isfinite(box[d]) || !(box[d] > 0.0))
            throw Error(STRUCTMD_ERR_UNSUPPORTED, path + ": the force coupling method needs a periodic box along x, y "
                                                         "and z, but the box is not periodic along " +
                                                         std::string(1, "xyz"[d]));
        wanted[d] = std::ceil(box[d] / spacing);
    }
    int sizes[3];
    checked_grid_sizes(wanted, 3, sizes, path + ".parameters.hydrodynamicRadius",
                       "the radius is too small for the box at this tolerance");
    plan.grid = FftGrid{sizes[0], sizes[1], sizes[2]};
    // The same support along every axis: enough points to span 2 reach on the finest one.
    double finest = spacing;
    for (int d = 0; d < 3; ++d) finest = std::min(finest, box[d] / sizes[d]);
    plan.support = static_cast<int>(std::ceil(2.0 * reach / finest)) + 1;
    for (int d = 0; d < 3; ++d)
        if (plan.support >= sizes[d])
            throw input_error(path + ".parameters.hydrodynamicRadius",
                              "the Gaussian of radius " + std::to_string(radius) + " spans " +
                                  std::to_string(plan.support) + " of the " + std::to_string(sizes[d]) +
                                  " grid points along " + std::string(1, "xyz"[d]) +
                                  ": the box is too small for this radius and tolerance");
    return plan;
}

template <class B, class R, class Green>
class FcmMesh {
public:
    FcmMesh(const B& backend, const FcmPlan& plan)
        : backend_(backend), plan_(plan), axes_(fcm_axes<R>(plan)), fft_(backend, plan.grid),
          bins_(backend, plan.grid.ny * plan.grid.nz) {
        backend_.resize(field_, static_cast<size_t>(3 * plan.grid.points()));
        backend_.resize(spectrum_, static_cast<size_t>(3 * plan.grid.spectrum_points()));
    }

    const FcmPlan& plan() const { return plan_; }

    // Fills displacement (flat, group members only) with dt M F + sqrt(2 kT dt) M^{1/2} W, M the
    // mobility of this kernel and G.
    void displace(const Particles<B, R>& p, const uint8_t* group, double dt, double kT, const Green& green,
                  uint64_t noiseStream, R* displacement) {
        const FftGrid grid = plan_.grid;
        const int64_t points = grid.points(), spectrumPoints = grid.spectrum_points();
        bins_.sort(p.count, GaussianKernelLine<R, FcmAxis<R>>{p.pos.data(), group, axes_});
        backend_.for_each_lanes(grid.ny * grid.nz,
                                GaussianSpreadLine<R, FcmAxis<R>, Real4Vectors<R>>{
                                    p.pos.data(), {p.force.data()}, bins_.order(), bins_.line_start(), axes_, field_.data()},
                                LaneSizing::kFillDevice);
        for (int d = 0; d < 3; ++d) fft_.forward(field_.data() + d * points, spectrum_.data() + d * spectrumPoints);
        const double volume = plan_.box[0] * plan_.box[1] * plan_.box[2];
        backend_.for_each(spectrumPoints,
                          FcmStokesSolve<R, Green>{spectrum_.data(), grid, p.box.length, green, R(dt / double(points)),
                                                   R(2.0 * kT * dt / volume), p.noise.seed, noiseStream, p.now()});
        for (int d = 0; d < 3; ++d) fft_.inverse(spectrum_.data() + d * spectrumPoints, field_.data() + d * points);
        backend_.for_each(p.count, GaussianInterpolate<R, FcmAxis<R>>{p.pos.data(), group, axes_, field_.data(),
                                                                      R(volume / double(points)), displacement});
    }

private:
    const B& backend_;
    FcmPlan plan_;
    FcmAxes<R> axes_;
    typename B::template Fft3d<R> fft_;
    LineBins<B> bins_;
    typename B::template Buffer<R> field_;  // the force density, then dt u + noise: x, y, z grids
    typename B::template Buffer<Complex<R>> spectrum_;
};
#endif

}  // namespace structmd
