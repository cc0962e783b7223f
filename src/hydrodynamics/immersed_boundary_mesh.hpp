#pragma once
// The fluctuating immersed boundary method (Delong, Balboa Usabiaga, Delgado-Buscalioni, Griffith &
// Donev, J. Chem. Phys. 140, 134110 (2014)) in a triply periodic box: the steady Stokes equations on
// a staggered grid (Balboa Usabiaga et al., Multiscale Model. Simul. 10, 1369 (2012)),
//   eta L v - grad p = -g,   div v = 0,
//   g = S F + sqrt(2 eta kT / (dt dV)) D W + (kT / delta) [S(q + delta/2 W~) - S(q - delta/2 W~)] W~,
// solved spectrally with the discrete operators' own symbols, and the particles' velocities J v.
//
// The grid: cell centres at x_i = -L/2 + i h; the x component of every vector field lives on the
// faces x_i + h/2 (index i), y and z alike along their axes. With that layout the divergence (faces
// to centres) is the backward difference, the gradient (centres to faces) the forward one, and the
// Laplacian the 7-point one on each component. In Fourier space, with d_a = (1 - exp(-i k_a h_a)) / h_a,
//   v_k = (g_k - conj(d) (d . g_k) / |d|^2) / (eta |d|^2),   k = 0 removed (no net flow),
// which is exactly the discrete projection P = I - G (DG)^{-1} D followed by the inverse Laplacian.
//
// S spreads a particle's vector with Peskin's 3-point kernel (peskin_kernel.hpp): component a at the
// a-faces with weight phi(dx/h) phi(dy/h) phi(dz/h) / dV; J = dV S^T averages the faces' velocities
// with the same weights. The random stress W is a symmetric tensor per cell: diagonal entries at the
// centres with variance 2, off-diagonal ones at the edges with variance 1, so that the divergence D W
// has covariance (-L) I + G G^H, whose gradient part the projection removes: the velocity's
// covariance is 2 kT / dt times the mobility's operator, and J of it 2 kT M / dt (fluctuation-
// dissipation on the discrete level). The last term of g is the random finite difference that gives
// kT times the divergence of S; the midpoint step (bdhi_fluctuating_immersed_boundary.hpp) gives the
// rest of kT div M.
//
// Spreading is one grid line along x per thread, from the particles sorted by the line their kernel
// window starts on (neighbour/line_bins.hpp), as the force coupling method does: no atomics on the grid.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "core/fft_grid.hpp"
#include "core/hd.hpp"
#include "core/random.hpp"
#include "core/vec.hpp"
#include "hydrodynamics/fcm_mesh.hpp"
#include "hydrodynamics/peskin_kernel.hpp"
#include "neighbour/line_bins.hpp"
#include "state/particles.hpp"
#include "state/step_clock.hpp"

namespace structmd {

// Everything the mesh needs for one box (make_immersed_boundary_plan).
struct ImmersedBoundaryPlan {
    FftGrid grid;
    double box[3] = {0, 0, 0};
    double spacing[3] = {0, 0, 0};
    double radius = 0.0;  // the hydrodynamic radius the kernel gives on this grid
};

// One periodic axis of the staggered grid, in grid units u = n (x / L + 1/2) (centres at integers).
template <class R>
struct StaggeredAxis {
    R inverseLength;  // 1 / L
    int n;

    SMD_HD SMD_INLINE R coordinate(R x) const { return R(n) * (x * inverseLength + R(0.5)); }
    // The first of the kPeskinWindow nodes that hold every weight of a particle at u, on the centres'
    // nodes (distance node - u) and on the faces' (node + 1/2 - u).
    SMD_HD SMD_INLINE int first(R u) const { return static_cast<int>(floor(u - R(0.5) * R(kPeskinWindow))) + 1; }
    SMD_HD SMD_INLINE int fold(int i) const {
        const int m = i % n;
        return m < 0 ? m + n : m;
    }
};

template <class R>
struct StaggeredAxes {
    StaggeredAxis<R> x, y, z;
    FftGrid grid;
    R inverseCellVolume;  // 1 / (hx hy hz)
};

#if SMD_HOST_CODE
template <class R>
inline StaggeredAxes<R> staggered_axes(const ImmersedBoundaryPlan& plan) {
    const int sizes[3] = {plan.grid.nx, plan.grid.ny, plan.grid.nz};
    StaggeredAxis<R> axis[3];
    for (int d = 0; d < 3; ++d) axis[d] = StaggeredAxis<R>{R(1.0 / plan.box[d]), sizes[d]};
    return {axis[0], axis[1], axis[2], plan.grid, R(1.0 / (plan.spacing[0] * plan.spacing[1] * plan.spacing[2]))};
}
#endif

// The weights of one node along one axis for a particle: on the centres' node and on the face half a
// cell above it.
template <class R>
struct NodeWeights {
    R centre, face;
    SMD_HD SMD_INLINE static NodeWeights at(R distance) { return {peskin3(distance), peskin3(distance + R(0.5))}; }
};

// The window start (y, z) a group member's kernel starts on, by which LineBins sorts the particles.
template <class R>
struct StaggeredKernelLine {
    const Real4<R>* pos;
    const uint8_t* group;
    StaggeredAxes<R> axes;
    SMD_HD int operator()(int64_t i) const {
        if (group && !group[i]) return -1;
        const Real4<R> r = pos[i];
        return axes.z.fold(axes.z.first(axes.z.coordinate(r.z))) * axes.grid.ny +
               axes.y.fold(axes.y.first(axes.y.coordinate(r.y)));
    }
};

// One grid line along x of the three face grids (x, y, z components, one after the other), cleared
// and then summed: S F of the particles whose window reaches it, and, where rfdNoise is given, the
// random finite difference rfdScale [S(q + offset) - S(q - offset)] W~ with offset = rfdHalfStep W~
// (rfdScale = kT / delta, rfdHalfStep = delta / 2).
template <class R>
struct StaggeredSpreadLine {
    const Real4<R>* pos;
    const Real4<R>* force;
    const R* rfdNoise;  // W~, flat; null: no random finite difference
    R rfdScale, rfdHalfStep;
    const int* order;
    const int* lineStart;
    StaggeredAxes<R> axes;
    R* field;

    SMD_HD void operator()(int64_t line) const {
        const FftGrid& g = axes.grid;
        const int64_t points = g.points();
        const int y = static_cast<int>(line % g.ny), z = static_cast<int>(line / g.ny);
        R* rows[3] = {field + g.index(0, y, z), nullptr, nullptr};
        rows[1] = rows[0] + points;
        rows[2] = rows[1] + points;
        for (int x = 0; x < g.nx; ++x) rows[0][x] = rows[1][x] = rows[2][x] = R(0);
        for (int c = 0; c < kPeskinWindow; ++c) {
            const int binZ = axes.z.fold(z - c);
            for (int b = 0; b < kPeskinWindow; ++b) {
                const int bin = binZ * g.ny + axes.y.fold(y - b);
                for (int s = lineStart[bin]; s < lineStart[bin + 1]; ++s) {
                    const int i = order[s];
                    const Real4<R> r = pos[i];
                    const Vec3<R> u{axes.x.coordinate(r.x), axes.y.coordinate(r.y), axes.z.coordinate(r.z)};
                    // This line's node along y and z, unfolded, relative to the particle.
                    const Vec3<R> node{R(0), R(axes.y.first(u.y) + b) - u.y, R(axes.z.first(u.z) + c) - u.z};
                    const Vec3<R> zero{R(0), R(0), R(0)};
                    const Real4<R> f = force[i];
                    deposit(rows, u.x, node, zero, Vec3<R>{f.x, f.y, f.z});
                    if (rfdNoise) {
                        const Vec3<R> w{rfdNoise[3 * i], rfdNoise[3 * i + 1], rfdNoise[3 * i + 2]};
                        // The offset in grid units along each axis.
                        const Vec3<R> offset{rfdHalfStep * w.x * R(axes.x.n) * axes.x.inverseLength,
                                             rfdHalfStep * w.y * R(axes.y.n) * axes.y.inverseLength,
                                             rfdHalfStep * w.z * R(axes.z.n) * axes.z.inverseLength};
                        deposit(rows, u.x, node, offset, rfdScale * w);
                        deposit(rows, u.x, node, R(-1) * offset, R(-1) * rfdScale * w);
                    }
                }
            }
        }
    }

    // Adds v, spread from u + offset (grid units), to this line: component a on the a-faces. The
    // offset is added to the node's distance rather than to u so that a small one keeps its digits.
    SMD_HD void deposit(R* const rows[3], R ux, Vec3<R> node, Vec3<R> offset, Vec3<R> v) const {
        const NodeWeights<R> wy = NodeWeights<R>::at(node.y - offset.y), wz = NodeWeights<R>::at(node.z - offset.z);
        const Vec3<R> scale{wy.centre * wz.centre * v.x, wy.face * wz.centre * v.y, wy.centre * wz.face * v.z};
        if (scale.x == R(0) && scale.y == R(0) && scale.z == R(0)) return;
        const int firstX = axes.x.first(ux);
        for (int a = 0; a < kPeskinWindow; ++a) {
            const NodeWeights<R> wx = NodeWeights<R>::at(R(firstX + a) - ux - offset.x);
            const int at = axes.x.fold(firstX + a);
            rows[0][at] += axes.inverseCellVolume * wx.face * scale.x;
            rows[1][at] += axes.inverseCellVolume * wx.centre * scale.y;
            rows[2][at] += axes.inverseCellVolume * wx.centre * scale.z;
        }
    }
};

// The random stress of one step: six N(0, 1) numbers per cell (xx, yy, zz at its centre; xy, xz, yz
// at the edges (x + h/2, y + h/2), (x + h/2, z + h/2), (y + h/2, z + h/2)), one grid after the other.
template <class R>
struct DrawRandomStress {
    R* stress;
    int64_t points;
    uint64_t seed, stream;
    ClockView now;
    SMD_HD void operator()(int64_t at) const {
        double xi[8];
        normal4(seed, stream ^ static_cast<uint64_t>(2 * at), static_cast<uint64_t>(now.step()), xi);
        normal4(seed, stream ^ static_cast<uint64_t>(2 * at + 1), static_cast<uint64_t>(now.step()), xi + 4);
        for (int c = 0; c < 6; ++c) stress[c * points + at] = R(xi[c]);
    }
};

// The faces of one cell gain amplitude (D W): the divergence of the random stress, the diagonal
// entries scaled by sqrt(2) to variance 2.
template <class R>
struct AddStressDivergence {
    const R* stress;
    R* field;
    StaggeredAxes<R> axes;
    Vec3<R> inverseSpacing;
    R amplitude;  // sqrt(2 eta kT / (dt dV))
    SMD_HD void operator()(int64_t at) const {
        const FftGrid& g = axes.grid;
        const int64_t points = g.points();
        const int x = static_cast<int>(at % g.nx), y = static_cast<int>((at / g.nx) % g.ny),
                  z = static_cast<int>(at / (int64_t(g.nx) * g.ny));
        const R* xx = stress;
        const R* yy = xx + points;
        const R* zz = yy + points;
        const R* xy = zz + points;
        const R* xz = xy + points;
        const R* yz = xz + points;
        const int64_t px = g.index(axes.x.fold(x + 1), y, z), mx = g.index(axes.x.fold(x - 1), y, z);
        const int64_t py = g.index(x, axes.y.fold(y + 1), z), my = g.index(x, axes.y.fold(y - 1), z);
        const int64_t pz = g.index(x, y, axes.z.fold(z + 1)), mz = g.index(x, y, axes.z.fold(z - 1));
        const R root2 = R(1.4142135623730951);
        const R dx = root2 * (xx[px] - xx[at]) * inverseSpacing.x + (xy[at] - xy[my]) * inverseSpacing.y +
                     (xz[at] - xz[mz]) * inverseSpacing.z;
        const R dy = (xy[at] - xy[mx]) * inverseSpacing.x + root2 * (yy[py] - yy[at]) * inverseSpacing.y +
                     (yz[at] - yz[mz]) * inverseSpacing.z;
        const R dz = (xz[at] - xz[mx]) * inverseSpacing.x + (yz[at] - yz[my]) * inverseSpacing.y +
                     root2 * (zz[pz] - zz[at]) * inverseSpacing.z;
        field[at] += amplitude * dx;
        field[at + points] += amplitude * dy;
        field[at + 2 * points] += amplitude * dz;
    }
};

// One wave vector of the half spectrum: the forcing's spectrum (three components, one spectrum after
// the other) becomes the velocity's, scaled by 1/N so that the unnormalised inverse transform gives v.
template <class R>
struct StaggeredStokesSolve {
    Complex<R>* spectrum;
    FftGrid grid;
    Vec3<R> inverseSpacing;
    R scale;  // 1 / (eta N)

    SMD_HD void operator()(int64_t at) const {
        const int64_t spectrumPoints = grid.spectrum_points();
        Complex<R>* f[3] = {spectrum + at, spectrum + at + spectrumPoints, spectrum + at + 2 * spectrumPoints};
        if (at == 0) {
            for (Complex<R>* c : f) *c = Complex<R>{R(0), R(0)};
            return;
        }
        const int hx = grid.half_x();
        const int index[3] = {static_cast<int>(at % hx), static_cast<int>((at / hx) % grid.ny),
                              static_cast<int>(at / (int64_t(hx) * grid.ny))};
        const int sizes[3] = {grid.nx, grid.ny, grid.nz};
        const R inverse[3] = {inverseSpacing.x, inverseSpacing.y, inverseSpacing.z};
        // d_a = (1 - exp(-i theta_a)) / h_a, theta_a = 2 pi m_a / n_a.
        R dRe[3], dIm[3], d2 = R(0);
        for (int a = 0; a < 3; ++a) {
            const R theta = R(6.283185307179586) * R(index[a]) / R(sizes[a]);
            dRe[a] = (R(1) - cos(theta)) * inverse[a];
            dIm[a] = sin(theta) * inverse[a];
            d2 += dRe[a] * dRe[a] + dIm[a] * dIm[a];
        }
        // (d . g), then g - conj(d) (d . g) / |d|^2, over eta |d|^2.
        R dotRe = R(0), dotIm = R(0);
        for (int a = 0; a < 3; ++a) {
            dotRe += dRe[a] * f[a]->re - dIm[a] * f[a]->im;
            dotIm += dRe[a] * f[a]->im + dIm[a] * f[a]->re;
        }
        const R s = scale / d2;
        for (int a = 0; a < 3; ++a) {
            const R re = f[a]->re - (dRe[a] * dotRe + dIm[a] * dotIm) / d2;
            const R im = f[a]->im - (dRe[a] * dotIm - dIm[a] * dotRe) / d2;
            *f[a] = Complex<R>{s * re, s * im};
        }
    }
};

// Each group member's velocity J v at `at` (its position, or its midpoint position), times `scale`,
// flat; 0 for the others. Component a is the a-faces' velocity averaged with the particle's weights.
template <class R>
struct StaggeredInterpolate {
    const Real4<R>* at;
    const uint8_t* group;
    StaggeredAxes<R> axes;
    const R* field;
    R scale;
    R* out;

    SMD_HD void operator()(int64_t i) const {
        Vec3<R> sum{R(0), R(0), R(0)};
        if (!group || group[i]) {
            const FftGrid& g = axes.grid;
            const int64_t points = g.points();
            const Real4<R> r = at[i];
            const Vec3<R> u{axes.x.coordinate(r.x), axes.y.coordinate(r.y), axes.z.coordinate(r.z)};
            const int firstX = axes.x.first(u.x), firstY = axes.y.first(u.y), firstZ = axes.z.first(u.z);
            NodeWeights<R> wx[kPeskinWindow];
            for (int a = 0; a < kPeskinWindow; ++a) wx[a] = NodeWeights<R>::at(R(firstX + a) - u.x);
            for (int c = 0; c < kPeskinWindow; ++c) {
                const NodeWeights<R> wz = NodeWeights<R>::at(R(firstZ + c) - u.z);
                for (int b = 0; b < kPeskinWindow; ++b) {
                    const NodeWeights<R> wy = NodeWeights<R>::at(R(firstY + b) - u.y);
                    const Vec3<R> wyz{wy.centre * wz.centre, wy.face * wz.centre, wy.centre * wz.face};
                    if (wyz.x == R(0) && wyz.y == R(0) && wyz.z == R(0)) continue;
                    const R* line = field + g.index(0, axes.y.fold(firstY + b), axes.z.fold(firstZ + c));
                    for (int a = 0; a < kPeskinWindow; ++a) {
                        const int x = axes.x.fold(firstX + a);
                        sum.x += wx[a].face * wyz.x * line[x];
                        sum.y += wx[a].centre * wyz.y * line[x + points];
                        sum.z += wx[a].centre * wyz.z * line[x + 2 * points];
                    }
                }
            }
        }
        out[3 * i] = scale * sum.x;
        out[3 * i + 1] = scale * sum.y;
        out[3 * i + 2] = scale * sum.z;
    }
};

// The midpoint q + halfStep (J v) (halfStep = dt / 2) of every particle, from its velocity.
template <class R>
struct MidpointPositions {
    const Real4<R>* pos;
    const R* velocity;
    R halfStep;
    Real4<R>* midpoint;
    SMD_HD void operator()(int64_t i) const {
        Real4<R> r = pos[i];
        r.x += halfStep * velocity[3 * i];
        r.y += halfStep * velocity[3 * i + 1];
        r.z += halfStep * velocity[3 * i + 2];
        midpoint[i] = r;
    }
};

#if SMD_HOST_CODE
// The FFT-friendly number of cells (fcm_mesh.hpp's fft_friendly_size: even, factors 2, 3 and 5) closest
// to `wanted` in ratio, so that the radius 0.91 L / n is the closest to the one asked for.
inline int closest_friendly_size(double wanted) {
    const int above = fft_friendly_size(static_cast<int>(std::ceil(wanted)));
    for (int below = static_cast<int>(std::floor(wanted)); below >= 2; --below)
        if (fft_friendly_size(below) == below)
            return std::fabs(wanted / below - 1.0) < std::fabs(wanted / above - 1.0) ? below : above;
    return above;
}

// The grid for a hydrodynamic radius a: the kernel gives a = 0.91 h, so L / h = 0.91 L / a cells
// along each axis, rounded to the closest FFT-friendly number (closest_friendly_size). The radius the
// kernel then gives is 0.91 times the spacing (the geometric mean where the spacings differ).
inline ImmersedBoundaryPlan make_immersed_boundary_plan(const double box[3], double radius, const std::string& path) {
    ImmersedBoundaryPlan plan;
    const double spacing = radius / kPeskin3RadiusOverSpacing;
    double wanted[3];
    for (int d = 0; d < 3; ++d) {
        plan.box[d] = box[d];
        if (!std::isfinite(box[d]) || !(box[d] > 0.0))
            throw Error(STRUCTMD_ERR_UNSUPPORTED, path + ": the immersed boundary method needs a periodic box along x, "
                                                         "y and z, but the box is not periodic along " +
                                                         std::string(1, "xyz"[d]));
        wanted[d] = box[d] / spacing;
    }
    int sizes[3];
    checked_grid_sizes(wanted, 3, sizes, path + ".parameters.hydrodynamicRadius",
                       "the radius is too small for the box");
    for (int d = 0; d < 3; ++d) {
        sizes[d] = closest_friendly_size(wanted[d]);
        if (sizes[d] < kPeskinWindow)
            throw input_error(path + ".parameters.hydrodynamicRadius",
                              "a radius of " + std::to_string(radius) + " needs cells of " + std::to_string(spacing) +
                                  ", fewer than " + std::to_string(kPeskinWindow) + " along " +
                                  std::string(1, "xyz"[d]) + ": the box is too small for this radius");
    }
    plan.grid = FftGrid{sizes[0], sizes[1], sizes[2]};
    for (int d = 0; d < 3; ++d) plan.spacing[d] = box[d] / sizes[d];
    plan.radius = kPeskin3RadiusOverSpacing * std::cbrt(plan.spacing[0] * plan.spacing[1] * plan.spacing[2]);
    return plan;
}

template <class B, class R>
class ImmersedBoundaryMesh {
public:
    ImmersedBoundaryMesh(const B& backend, const ImmersedBoundaryPlan& plan)
        : backend_(backend), plan_(plan), axes_(staggered_axes<R>(plan)), fft_(backend, plan.grid),
          bins_(backend, plan.grid.ny * plan.grid.nz) {
        backend_.resize(field_, static_cast<size_t>(3 * plan.grid.points()));
        backend_.resize(spectrum_, static_cast<size_t>(3 * plan.grid.spectrum_points()));
    }

    const ImmersedBoundaryPlan& plan() const { return plan_; }

    // The fluid's velocity on the faces for the particles' forces, the random finite difference
    // (rfdNoise: W~ flat, null at kT = 0) and the random stress (at kT > 0).
    void solve(const Particles<B, R>& p, const uint8_t* group, double dt, double viscosity, double kT,
               const R* rfdNoise, double rfdDelta, uint64_t noiseStream) {
        const FftGrid grid = plan_.grid;
        const int64_t points = grid.points(), spectrumPoints = grid.spectrum_points();
        bins_.sort(p.count, StaggeredKernelLine<R>{p.pos.data(), group, axes_});
        backend_.for_each(grid.ny * grid.nz,
                          StaggeredSpreadLine<R>{p.pos.data(), p.force.data(), rfdNoise, R(kT / rfdDelta),
                                                 R(0.5 * rfdDelta), bins_.order(), bins_.line_start(), axes_,
                                                 field_.data()});
        const Vec3<R> inverseSpacing{R(1.0 / plan_.spacing[0]), R(1.0 / plan_.spacing[1]), R(1.0 / plan_.spacing[2])};
        if (kT > 0.0) {
            backend_.resize(stress_, static_cast<size_t>(6 * points));
            backend_.for_each(points, DrawRandomStress<R>{stress_.data(), points, p.noise.seed, noiseStream, p.now()});
            const double cellVolume = plan_.spacing[0] * plan_.spacing[1] * plan_.spacing[2];
            backend_.for_each(points, AddStressDivergence<R>{stress_.data(), field_.data(), axes_, inverseSpacing,
                                                             R(std::sqrt(2.0 * viscosity * kT / (dt * cellVolume)))});
        }
        for (int d = 0; d < 3; ++d) fft_.forward(field_.data() + d * points, spectrum_.data() + d * spectrumPoints);
        backend_.for_each(spectrumPoints, StaggeredStokesSolve<R>{spectrum_.data(), grid, inverseSpacing,
                                                                  R(1.0 / (viscosity * double(points)))});
        for (int d = 0; d < 3; ++d) fft_.inverse(spectrum_.data() + d * spectrumPoints, field_.data() + d * points);
    }

    // scale J v at the positions `at` (flat, group members only), v the last solve's velocity.
    void interpolate(int64_t count, const Real4<R>* at, const uint8_t* group, double scale, R* out) const {
        backend_.for_each(count, StaggeredInterpolate<R>{at, group, axes_, field_.data(), R(scale), out});
    }

private:
    const B& backend_;
    ImmersedBoundaryPlan plan_;
    StaggeredAxes<R> axes_;
    typename B::template Fft3d<R> fft_;
    LineBins<B> bins_;
    typename B::template Buffer<R> field_;   // the forcing, then the velocity: x, y, z face grids
    typename B::template Buffer<R> stress_;  // the random stress, at kT > 0
    typename B::template Buffer<Complex<R>> spectrum_;
};
#endif

}  // namespace structmd
