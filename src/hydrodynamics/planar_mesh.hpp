#pragma once
// Hydrodynamics of particles that move in a plane periodic along x and y (UAMMD's BDHI::BDHI2D; Pelaez
// et al., J. Stat. Mech. 063207 (2018)): the in-plane displacement of every particle in one step of
// Brownian dynamics,
//   dx = dt M F + dt kT div M + sqrt(2 kT dt) M^{1/2} W,    M = J K S,
// S spreading each force's x and y with the 2D Gaussian g(r) = (2 pi sigma^2)^{-1} exp(-r^2 / (2 sigma^2))
// onto a 2D grid (the particle's z is ignored: every particle counts as lying in the plane), K the
// kernel of hydrodynamics/planar_kernels.hpp in Fourier space (k = 0 removed: no net flow), J = S^T
// the same Gaussian's average of the velocity at the particle.
//
// The noise is a random velocity field drawn in Fourier space with covariance 2 kT dt K, added to
// the deterministic one before the inverse transform: averaged by J it has covariance 2 kT dt M
// exactly, for the same grid and kernel. The thermal drift kT sum_b d/dq_b . M(q_a - q_b) is the
// field -kT div K convolved with the particles' density spread by S, (i k . K)_i = i L(k) k_i / eta in
// Fourier space: it is not zero where the kernel is compressible (quasi-2D), and needs only the
// density's transform beside the forces'. Each particle's own term vanishes, on the grid too: the
// grid's div K is odd and J = S^T.
//
// The Nyquist lines of the grid are left out of every part, as the 3D force coupling method does
// (hydrodynamics/fcm_mesh.hpp, whose Gaussian axes and grid sizes this mesh shares).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "core/fft_grid.hpp"
#include "core/hd.hpp"
#include "core/random.hpp"
#include "core/vec.hpp"
#include "hydrodynamics/fcm_mesh.hpp"
#include "hydrodynamics/planar_kernels.hpp"
#include "neighbour/line_bins.hpp"
#include "state/particles.hpp"
#include "state/step_clock.hpp"

namespace structmd {

// Everything the mesh needs, fixed for one box (make_planar_plan); the grid's nz is 1.
struct PlanarPlan {
    FftGrid grid;
    double box[2] = {0, 0};
    double sigma = 0.0;
    int support = 0;
    PlanarHydrodynamics kind = PlanarHydrodynamics::quasi2D;
};

template <class R>
struct PlanarAxes {
    FcmAxis<R> x, y;
    FftGrid grid;
};

#if SMD_HOST_CODE
template <class R>
inline PlanarAxes<R> planar_axes(const PlanarPlan& plan) {
    const int sizes[2] = {plan.grid.nx, plan.grid.ny};
    FcmAxis<R> axis[2];
    for (int d = 0; d < 2; ++d)
        axis[d] = FcmAxis<R>{R(plan.box[d] / sizes[d]), R(1.0 / plan.box[d]), sizes[d], plan.support,
                             R(0.5 / (plan.sigma * plan.sigma)), R(1.0 / std::sqrt(2.0 * M_PI * plan.sigma * plan.sigma))};
    return {axis[0], axis[1], plan.grid};
}
#endif

// The grid line along x a group member's kernel starts on, by which LineBins sorts the particles.
template <class R>
struct PlanarKernelLine {
    const Real4<R>* pos;
    const uint8_t* group;
    PlanarAxes<R> axes;
    SMD_HD int operator()(int64_t i) const {
        if (group && !group[i]) return -1;
        return axes.y.fold(axes.y.first(axes.y.coordinate(pos[i].y)));
    }
};

// One grid line along x of the force-density grids (x, y components, then the particles' number
// density where the drift needs it), cleared and then summed: a particle whose kernel starts on line
// y - b adds F g_x g_y[b] along the line. Bins in b order and each in particle order. Each lane
// sums the points it owns (core/lanes.hpp's owns_point), so any power-of-two number of lanes gives
// the same sums; launched with LaneSizing::kFillDevice, as GaussianSpreadLine is.
template <class R>
struct PlanarSpreadLine {
    const Real4<R>* pos;
    const Real4<R>* force;
    const int* order;
    const int* lineStart;
    PlanarAxes<R> axes;
    R* density;
    bool withNumberDensity;

    SMD_HD void operator()(int64_t line, Lanes lanes) const {
        const FftGrid& g = axes.grid;
        const int64_t points = g.points();
        const int y = static_cast<int>(line);
        R* rowX = density + g.index(0, y, 0);
        R* rowY = rowX + points;
        R* rowN = rowY + points;
        for (int x = lanes.lane; x < g.nx; x += lanes.count) rowX[x] = rowY[x] = R(0);
        if (withNumberDensity)
            for (int x = lanes.lane; x < g.nx; x += lanes.count) rowN[x] = R(0);
        const int support = axes.x.support;
        for (int b = 0; b < support; ++b) {
            const int bin = axes.y.fold(y - b);
            for (int s = lineStart[bin]; s < lineStart[bin + 1]; ++s) {
                const int i = order[s];
                const Real4<R> r = pos[i];
                const R uy = axes.y.coordinate(r.y);
                const R wy = axes.y.weight(axes.y.first(uy), b, uy);
                const Real4<R> f = force[i];
                const R ux = axes.x.coordinate(r.x);
                const int firstX = axes.x.first(ux);
                for (int a = 0; a < support; ++a) {
                    const int at = axes.x.fold(firstX + a);
                    if (!owns_point(lanes, at)) continue;
                    const R w = wy * axes.x.weight(firstX, a, ux);
                    rowX[at] += w * f.x;
                    rowY[at] += w * f.y;
                    if (withNumberDensity) rowN[at] += w;
                }
            }
        }
    }
};

// t k^perp k^perp^T + l k^ k^T applied to the real 2-vector (v, w), k^ = (ux, uy), k^perp = (-uy, ux).
template <class R>
SMD_HD SMD_INLINE void planar_project(R ux, R uy, R v, R w, R t, R l, R& outX, R& outY) {
    const R along = l * (ux * v + uy * w), across = t * (-uy * v + ux * w);
    outX = along * ux - across * uy;
    outY = along * uy + across * ux;
}

// One wave vector of the half spectrum: the transformed force density (x, y spectra, one after the
// other) becomes the displacement field's spectrum,
//   A_k = dt/(N eta) K_k F_k  -  i dt kT/(N eta) L(k) k n_k  +  sqrt(2 kT dt / (A eta)) K_k^{1/2} Z_k,
// K_k = T(k) k^perp k^perp^T + L(k) k^ k^T, N the grid's points, A the box's area, n_k the number
// density's transform (only where the drift is wanted), Z_k a complex normal 2-vector with
// <Z Z^H> = I. The inverse transform (unnormalised) then gives the displacement field on the grid.
// On the line x = 0 the spectrum holds both k and -k: the one of higher index takes the conjugate of
// its partner's noise (K^{1/2} is even in k), so that the field is real.
template <class R>
struct PlanarStokesSolve {
    Complex<R>* spectrum;             // x, y force spectra in, displacement spectra out
    const Complex<R>* numberDensity;  // null: no thermal drift
    FftGrid grid;
    R lengthX, lengthY;
    PlanarKernel<R> kernel;
    R driftScale;    // dt / (N eta)
    R thermalScale;  // dt kT / (N eta)
    R noiseScale;    // 2 kT dt / (A eta); 0: no noise
    uint64_t seed, noiseStream;
    ClockView now;  // the step keys the noise

    SMD_HD void operator()(int64_t at) const {
        const int hx = grid.half_x();
        Complex<R>* fx = spectrum + at;
        Complex<R>* fy = fx + grid.spectrum_points();
        const int x = static_cast<int>(at % hx);
        const int y = static_cast<int>(at / hx);
        if (at == 0 || 2 * x == grid.nx || 2 * y == grid.ny) {
            *fx = *fy = Complex<R>{R(0), R(0)};
            return;
        }
        const R twoPi = R(6.283185307179586);
        const R kx = twoPi * R(x) / lengthX, ky = twoPi * R(2 * y < grid.ny ? y : y - grid.ny) / lengthY;
        const R k = sqrt(kx * kx + ky * ky);
        const R ux = kx / k, uy = ky / k;  // k^; k^perp = (-uy, ux)
        R transverse, longitudinal;
        kernel(k, transverse, longitudinal);
        R reX, reY, imX, imY;
        planar_project(ux, uy, fx->re, fy->re, driftScale * transverse, driftScale * longitudinal, reX, reY);
        planar_project(ux, uy, fx->im, fy->im, driftScale * transverse, driftScale * longitudinal, imX, imY);
        if (numberDensity) {
            // -i c L k n: the real part takes c L k Im n, the imaginary part -c L k Re n.
            const Complex<R> n = numberDensity[at];
            const R c = thermalScale * longitudinal;
            reX += c * kx * n.im;
            reY += c * ky * n.im;
            imX -= c * kx * n.re;
            imY -= c * ky * n.re;
        }
        if (noiseScale > R(0)) {
            int64_t drawn = at;
            R conjugate = R(1);
            if (x == 0) {
                const int64_t partner = int64_t(hx) * ((grid.ny - y) % grid.ny);
                if (partner < at) {
                    drawn = partner;
                    conjugate = R(-1);
                }
            }
            double xi[4];
            normal4(seed, noiseStream ^ static_cast<uint64_t>(drawn), static_cast<uint64_t>(now.step()), xi);
            const R half = noiseScale * R(0.5);  // re and im each carry half
            const R rootT = sqrt(half * transverse), rootL = sqrt(half * longitudinal);
            R nX, nY;
            planar_project(ux, uy, R(xi[0]), R(xi[1]), rootT, rootL, nX, nY);
            reX += nX;
            reY += nY;
            planar_project(ux, uy, R(xi[2]), R(xi[3]), rootT, rootL, nX, nY);
            imX += conjugate * nX;
            imY += conjugate * nY;
        }
        *fx = Complex<R>{reX, imX};
        *fy = Complex<R>{reY, imY};
    }
};

// Each group member's displacement: the grid's field averaged by its Gaussian, times the cell
// area. z is not moved.
template <class R>
struct PlanarInterpolate {
    const Real4<R>* pos;
    const uint8_t* group;
    PlanarAxes<R> axes;
    const R* field;  // two grids, x and y components
    R cellArea;
    R* displacement;  // flat, three numbers a particle

    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        const FftGrid& g = axes.grid;
        const int64_t points = g.points();
        const Real4<R> r = pos[i];
        const R ux = axes.x.coordinate(r.x), uy = axes.y.coordinate(r.y);
        const int firstX = axes.x.first(ux), firstY = axes.y.first(uy);
        const int support = axes.x.support;
        R sumX = R(0), sumY = R(0);
        for (int b = 0; b < support; ++b) {
            const R wy = axes.y.weight(firstY, b, uy);
            const R* line = field + g.index(0, axes.y.fold(firstY + b), 0);
            for (int a = 0; a < support; ++a) {
                const int at = axes.x.fold(firstX + a);
                const R w = wy * axes.x.weight(firstX, a, ux);
                sumX += w * line[at];
                sumY += w * line[at + points];
            }
        }
        displacement[3 * i] = cellArea * sumX;
        displacement[3 * i + 1] = cellArea * sumY;
        displacement[3 * i + 2] = R(0);
    }
};

#if SMD_HOST_CODE
// The Gaussian's width for a hydrodynamic radius a: quasi-2D's is the 3D force coupling method's,
// a / sqrt(pi), true 2D's UAMMD's fit (planar_kernels.hpp).
inline double planar_sigma(PlanarHydrodynamics kind, double radius) {
    return kind == PlanarHydrodynamics::true2D ? 0.66556976637237890625 * radius : radius / std::sqrt(M_PI);
}

// The grid and the kernel's support for a hydrodynamic radius and tolerance, chosen as the 3D force
// coupling method chooses them (make_fcm_plan) from the Gaussian's width; UAMMD's BDHI2D ignores the
// tolerance (a spacing of 0.8 a, 3 a of support).
inline PlanarPlan make_planar_plan(const double box[2], PlanarHydrodynamics kind, double radius, double tolerance,
                                   const std::string& path) {
    PlanarPlan plan;
    plan.kind = kind;
    plan.sigma = planar_sigma(kind, radius);
    const double upsampling = std::min(0.55 + (-std::log10(3.0 * tolerance) / 10.0) * (1.65 - 0.55), 1.65);
    const double spacing = plan.sigma / upsampling;
    const double reach = plan.sigma * std::sqrt(2.0 * std::log(1.0 / tolerance));
    double wanted[2];
    for (int d = 0; d < 2; ++d) {
        plan.box[d] = box[d];
        if (!std::isfinite(box[d]) || !(box[d] > 0.0))
            throw Error(STRUCTMD_ERR_UNSUPPORTED, path + ": [\"BDHIDoublyPeriodic\", \"Quasi2D\"] needs a box periodic "
                                                         "along x and y, but the box is not periodic along " +
                                                         std::string(1, "xy"[d]));
        wanted[d] = std::ceil(box[d] / spacing);
    }
    int sizes[2];
    checked_grid_sizes(wanted, 2, sizes, path + ".parameters.hydrodynamicRadius",
                       "the radius is too small for the box at this tolerance");
    plan.grid = FftGrid{sizes[0], sizes[1], 1};
    const double finest = std::min(box[0] / sizes[0], box[1] / sizes[1]);
    plan.support = static_cast<int>(std::ceil(2.0 * reach / finest)) + 1;
    for (int d = 0; d < 2; ++d)
        if (plan.support >= sizes[d])
            throw input_error(path + ".parameters.hydrodynamicRadius",
                              "the Gaussian of radius " + std::to_string(radius) + " spans " +
                                  std::to_string(plan.support) + " of the " + std::to_string(sizes[d]) +
                                  " grid points along " + std::string(1, "xy"[d]) +
                                  ": the box is too small for this radius and tolerance");
    return plan;
}

template <class B, class R>
class PlanarMesh {
public:
    PlanarMesh(const B& backend, const PlanarPlan& plan)
        : backend_(backend), plan_(plan), axes_(planar_axes<R>(plan)), fft_(backend, plan.grid),
          bins_(backend, plan.grid.ny) {
        backend_.resize(field_, static_cast<size_t>(3 * plan.grid.points()));
        backend_.resize(spectrum_, static_cast<size_t>(3 * plan.grid.spectrum_points()));
    }

    const PlanarPlan& plan() const { return plan_; }

    // Fills displacement (by particle, group members only) with dt M F + dt kT div M +
    // sqrt(2 kT dt) M^{1/2} W, in x and y.
    void displace(const Particles<B, R>& p, const uint8_t* group, double dt, double viscosity, double kT,
                  uint64_t noiseStream, R* displacement) {
        const FftGrid grid = plan_.grid;
        const int64_t points = grid.points(), spectrumPoints = grid.spectrum_points();
        const PlanarKernel<R> kernel{plan_.kind, R(plan_.sigma)};
        const bool drift = kT > 0.0 && kernel.compressible();
        bins_.sort(p.count, PlanarKernelLine<R>{p.pos.data(), group, axes_});
        backend_.for_each_lanes(grid.ny,
                                PlanarSpreadLine<R>{p.pos.data(), p.force.data(), bins_.order(), bins_.line_start(), axes_,
                                                    field_.data(), drift},
                                LaneSizing::kFillDevice);
        for (int d = 0; d < (drift ? 3 : 2); ++d)
            fft_.forward(field_.data() + d * points, spectrum_.data() + d * spectrumPoints);
        const double area = plan_.box[0] * plan_.box[1];
        backend_.for_each(spectrumPoints,
                          PlanarStokesSolve<R>{spectrum_.data(), drift ? spectrum_.data() + 2 * spectrumPoints : nullptr,
                                               grid, R(plan_.box[0]), R(plan_.box[1]), kernel,
                                               R(dt / (double(points) * viscosity)),
                                               R(dt * kT / (double(points) * viscosity)),
                                               R(2.0 * kT * dt / (area * viscosity)), p.noise.seed, noiseStream, p.now()});
        for (int d = 0; d < 2; ++d) fft_.inverse(spectrum_.data() + d * spectrumPoints, field_.data() + d * points);
        backend_.for_each(p.count, PlanarInterpolate<R>{p.pos.data(), group, axes_, field_.data(),
                                                        R(area / double(points)), displacement});
    }

private:
    const B& backend_;
    PlanarPlan plan_;
    PlanarAxes<R> axes_;
    typename B::template Fft3d<R> fft_;
    LineBins<B> bins_;
    typename B::template Buffer<R> field_;  // force x, y and number density, then the displacement's x, y
    typename B::template Buffer<Complex<R>> spectrum_;
};
#endif

}  // namespace structmd
