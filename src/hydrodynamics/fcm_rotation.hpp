#pragma once
// The force coupling method with rotation (Lomholt & Maxey, J. Comput. Phys. 184, 381 (2003);
// Keaveny, J. Comput. Phys. 269, 61 (2014)) in a triply periodic box: the displacement and the
// rotation of every particle in one step of Brownian dynamics with hydrodynamic interactions. The
// fluid is driven by the forces spread with fcm_mesh.hpp's Gaussian g (width sigma = a / sqrt(pi))
// and by the torques spread as the curl of a narrower Gaussian g_t,
//   f(x) = sum_i F_i g(x - x_i) + (1/2) curl sum_i T_i g_t(x - x_i),   sigma_t = a / (6 sqrt(pi))^(1/3),
// the width for which an isolated sphere turns at the Stokes rate T / (8 pi eta a^3). Each particle
// moves with the velocity averaged by g and turns with half the curl of the velocity (the fluid's
// local angular velocity) averaged by g_t:
//   dx_i = dt int g(x - x_i) u(x) dx,   dtheta_i = dt int g_t(x - x_i) (1/2) curl u(x) dx.
// Spreading is the adjoint of averaging and the curl is its own adjoint, so the mobility of forces
// and torques together is symmetric; the fluid's random velocity (FcmStokesSolve's) averaged the
// same way gives the displacements and rotations their covariance 2 kT dt times it.
//
// The curls are taken in Fourier space, (curl v)_k = i k x v_k. The grid is made fine enough for the
// narrower g_t at the tolerance asked (make_fcm_plan's resolvedSigma), and each kernel has its own
// support.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "hydrodynamics/fcm_mesh.hpp"

namespace structmd {

// The torque's Gaussian width for a hydrodynamic radius a.
inline double fcm_torque_sigma(double radius) { return radius / std::cbrt(6.0 * std::sqrt(M_PI)); }

// The two kernels on one grid: the forces' (translation) and the torques' (same grid, its own
// width and support).
struct FcmRotationPlan {
    FcmPlan translation;
    FcmPlan rotation;
};

#if SMD_HOST_CODE
inline FcmRotationPlan make_fcm_rotation_plan(const double box[3], double radius, double tolerance,
                                              const std::string& path) {
    FcmRotationPlan plan;
    const double torqueSigma = fcm_torque_sigma(radius);
    plan.translation = make_fcm_plan(box, radius, tolerance, path, torqueSigma);
    plan.rotation = plan.translation;
    plan.rotation.sigma = torqueSigma;
    const int sizes[3] = {plan.translation.grid.nx, plan.translation.grid.ny, plan.translation.grid.nz};
    double finest = box[0] / sizes[0];
    for (int d = 1; d < 3; ++d) finest = std::min(finest, box[d] / sizes[d]);
    const double reach = torqueSigma * std::sqrt(2.0 * std::log(1.0 / tolerance));
    plan.rotation.support = static_cast<int>(std::ceil(2.0 * reach / finest)) + 1;
    return plan;
}
#endif

// to_k (+)= (i/2) k x from_k at one wave vector of the half spectrum (three components, one spectrum
// after the other): half the curl, in Fourier space, of the field whose spectrum `from` holds.
template <class R>
struct FcmHalfCurl {
    const Complex<R>* from;
    Complex<R>* to;
    FftGrid grid;
    Vec3<R> length;
    bool accumulate;  // add to `to` (the torques' flow onto the forces'); else overwrite it

    SMD_HD void operator()(int64_t at) const {
        const int hx = grid.half_x();
        const int64_t spectrumPoints = grid.spectrum_points();
        const int x = static_cast<int>(at % hx);
        const int y = static_cast<int>((at / hx) % grid.ny);
        const int z = static_cast<int>(at / (int64_t(hx) * grid.ny));
        const R twoPi = R(6.283185307179586);
        const Vec3<R> halfK{R(0.5) * twoPi * R(x) / length.x,
                            R(0.5) * twoPi * R(2 * y < grid.ny ? y : y - grid.ny) / length.y,
                            R(0.5) * twoPi * R(2 * z < grid.nz ? z : z - grid.nz) / length.z};
        const Complex<R>* a = from + at;
        const Vec3<R> re{a[0].re, a[spectrumPoints].re, a[2 * spectrumPoints].re};
        const Vec3<R> im{a[0].im, a[spectrumPoints].im, a[2 * spectrumPoints].im};
        // i (k/2) x (re + i im) = -(k/2) x im + i (k/2) x re
        const Vec3<R> curlRe = R(-1) * cross(halfK, im);
        const Vec3<R> curlIm = cross(halfK, re);
        const R cr[3] = {curlRe.x, curlRe.y, curlRe.z}, ci[3] = {curlIm.x, curlIm.y, curlIm.z};
        for (int d = 0; d < 3; ++d) {
            Complex<R>& out = to[at + d * spectrumPoints];
            out = accumulate ? Complex<R>{out.re + cr[d], out.im + ci[d]} : Complex<R>{cr[d], ci[d]};
        }
    }

private:
    SMD_HD SMD_INLINE static Vec3<R> cross(const Vec3<R>& a, const Vec3<R>& b) {
        return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    }
};

#if SMD_HOST_CODE
template <class B, class R>
class FcmRotationMesh {
public:
    FcmRotationMesh(const B& backend, const FcmRotationPlan& plan)
        : backend_(backend), plan_(plan), forceAxes_(fcm_axes<R>(plan.translation)),
          torqueAxes_(fcm_axes<R>(plan.rotation)), fft_(backend, plan.translation.grid),
          bins_(backend, plan.translation.grid.ny * plan.translation.grid.nz) {
        const FftGrid& grid = plan.translation.grid;
        backend_.resize(field_, static_cast<size_t>(3 * grid.points()));
        backend_.resize(spectrum_, static_cast<size_t>(3 * grid.spectrum_points()));
        backend_.resize(curl_, static_cast<size_t>(3 * grid.spectrum_points()));
    }

    const FcmRotationPlan& plan() const { return plan_; }

    // Fills displacement and rotation (flat, group members only; rotation vectors in the lab frame)
    // with the step's translation and rotation by the forces, the torques and, at kT > 0, the noise.
    void move(const Particles<B, R>& p, const uint8_t* group, double dt, double kT, double viscosity,
              uint64_t noiseStream, R* displacement, R* rotation) {
        const FftGrid grid = plan_.translation.grid;
        const int64_t points = grid.points(), spectrumPoints = grid.spectrum_points();
        spread(p, group, forceAxes_, p.force.data(), spectrum_.data());
        spread(p, group, torqueAxes_, p.torque.data(), curl_.data());
        backend_.for_each(spectrumPoints, FcmHalfCurl<R>{curl_.data(), spectrum_.data(), grid, p.box.length, true});
        const double volume = plan_.translation.box[0] * plan_.translation.box[1] * plan_.translation.box[2];
        backend_.for_each(spectrumPoints, FcmStokesSolve<R, FcmGreen<R>>{
                                              spectrum_.data(), grid, p.box.length, FcmGreen<R>{R(1.0 / viscosity)},
                                              R(dt / double(points)), R(2.0 * kT * dt / volume), p.noise.seed,
                                              noiseStream, p.now()});
        backend_.for_each(spectrumPoints, FcmHalfCurl<R>{spectrum_.data(), curl_.data(), grid, p.box.length, false});
        const R cellVolume = R(volume / double(points));
        for (int d = 0; d < 3; ++d) fft_.inverse(spectrum_.data() + d * spectrumPoints, field_.data() + d * points);
        backend_.for_each(p.count, GaussianInterpolate<R, FcmAxis<R>>{p.pos.data(), group, forceAxes_, field_.data(),
                                                                      cellVolume, displacement});
        for (int d = 0; d < 3; ++d) fft_.inverse(curl_.data() + d * spectrumPoints, field_.data() + d * points);
        backend_.for_each(p.count, GaussianInterpolate<R, FcmAxis<R>>{p.pos.data(), group, torqueAxes_, field_.data(),
                                                                      cellVolume, rotation});
    }

private:
    // The spectrum of the group's vectors spread with one kernel.
    void spread(const Particles<B, R>& p, const uint8_t* group, const FcmAxes<R>& axes, const Real4<R>* vectors,
                Complex<R>* spectrum) {
        const FftGrid grid = plan_.translation.grid;
        bins_.sort(p.count, GaussianKernelLine<R, FcmAxis<R>>{p.pos.data(), group, axes});
        backend_.for_each_lanes(grid.ny * grid.nz,
                                GaussianSpreadLine<R, FcmAxis<R>, Real4Vectors<R>>{
                                    p.pos.data(), {vectors}, bins_.order(), bins_.line_start(), axes, field_.data()},
                                LaneSizing::kFillDevice);
        for (int d = 0; d < 3; ++d)
            fft_.forward(field_.data() + d * grid.points(), spectrum + d * grid.spectrum_points());
    }

    const B& backend_;
    FcmRotationPlan plan_;
    FcmAxes<R> forceAxes_, torqueAxes_;
    typename B::template Fft3d<R> fft_;
    LineBins<B> bins_;
    typename B::template Buffer<R> field_;  // a density, then a field: x, y, z grids
    typename B::template Buffer<Complex<R>> spectrum_;  // the forces' (and torques') flow
    typename B::template Buffer<Complex<R>> curl_;      // the torques' spectrum, then half the flow's curl
};
#endif

}  // namespace structmd
