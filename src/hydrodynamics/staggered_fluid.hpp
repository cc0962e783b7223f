#pragma once
// The incompressible fluctuating fluid of the inertial coupling method (integrators/
// fluctuating_hydrodynamics_icm.hpp; Balboa Usabiaga et al., Comput. Methods Appl. Mech. Eng. 269,
// 139 (2014), and "Staggered schemes for fluctuating hydrodynamics", Multiscale Model. Simul. 10,
// 1369 (2012)) on a staggered grid in a triply periodic box, and its coupling to the particles.
//
// The box [-L/2, L/2)^3 is cut into n_x n_y n_z cells of sides h; velocity component alpha of cell r
// lives on the cell's upper face along alpha, at the box corner + (r + 1/2 + e_alpha / 2) h. A field
// is three grids of cells (x, y, z components, one after the other, core/fft_grid.hpp's layout). The
// discrete operators: divergence D (face to centre), gradient G = -D^* (centre to face), the
// Laplacian L (seven points per component), the projection onto divergence-free fields
// P = I - G (D G)^{-1} D; in Fourier space, with theta_d = 2 pi m_d / n_d,
//   D_d = (1 - e^{-i theta_d}) / h_d,   |D|^2 = sum_d (2 sin(theta_d / 2) / h_d)^2 = -L,
//   P = I - conj(D) D^T / |D|^2.
// Particles meet the fluid through Peskin's three-point kernel (peskin_kernel.hpp): the
// velocity at a particle J v = sum_faces phi phi phi v (J = dV S^T), and a force f spread as the
// force density S f = sum_faces phi phi phi f / dV.
#include <cmath>
#include <cstdint>

#include "core/fft_grid.hpp"
#include "core/hd.hpp"
#include "core/random.hpp"
#include "core/vec.hpp"
#include "hydrodynamics/peskin_kernel.hpp"
#include "state/step_clock.hpp"

namespace structmd {

template <class R>
struct StaggeredGrid {
    FftGrid cells;
    Vec3<R> length;   // L
    Vec3<R> spacing;  // h = L / n

    SMD_HD SMD_INLINE static int fold(int i, int n) {
        const int m = i % n;
        return m < 0 ? m + n : m;
    }
    // The position in cells from the box's lower corner, in [0, n) for a wrapped position.
    SMD_HD SMD_INLINE R coordinate(R x, int axis) const {
        const R l = axis == 0 ? length.x : axis == 1 ? length.y : length.z;
        const int n = axis == 0 ? cells.nx : axis == 1 ? cells.ny : cells.nz;
        return R(n) * (x / l + R(0.5));
    }
    SMD_HD SMD_INLINE int size(int axis) const { return axis == 0 ? cells.nx : axis == 1 ? cells.ny : cells.nz; }
    SMD_HD SMD_INLINE R h(int axis) const { return axis == 0 ? spacing.x : axis == 1 ? spacing.y : spacing.z; }
    // The index of cell r + (dx, dy, dz), folded into the box.
    SMD_HD SMD_INLINE int64_t at(int x, int y, int z, int dx, int dy, int dz) const {
        return cells.index(fold(x + dx, cells.nx), fold(y + dy, cells.ny), fold(z + dz, cells.nz));
    }
};

// One particle's kernel weights along the three axes: the four grid nodes from its cell - 2 on, at
// the cell centres (offset 1/2) and at the upper faces (offset 1): component alpha reads the face
// weights along alpha and the centre weights along the other two axes.
template <class R>
struct PeskinWeights {
    int first[3];     // the unfolded index of the first node along each axis
    R centre[3][4];   // phi(first + j + 1/2 - u)
    R face[3][4];     // phi(first + j + 1 - u)

    SMD_HD SMD_INLINE PeskinWeights(const StaggeredGrid<R>& g, const Real4<R>& p) {
        const R position[3] = {p.x, p.y, p.z};
        for (int d = 0; d < 3; ++d) {
            const R u = g.coordinate(position[d], d);
            first[d] = static_cast<int>(floor(u)) - 2;
            for (int j = 0; j < 4; ++j) {
                centre[d][j] = peskin3(R(first[d] + j) + R(0.5) - u);
                face[d][j] = peskin3(R(first[d] + j) + R(1) - u);
            }
        }
    }
    SMD_HD SMD_INLINE R weight(int component, int axis, int j) const {
        return component == axis ? face[axis][j] : centre[axis][j];
    }
};

// The grid line (y, z) of the cell a group member stands in, by which LineBins sorts the particles.
template <class R>
struct StaggeredParticleLine {
    const Real4<R>* pos;
    const uint8_t* group;
    StaggeredGrid<R> grid;
    SMD_HD int operator()(int64_t i) const {
        if (group && !group[i]) return -1;
        const Real4<R> r = pos[i];
        const int y = StaggeredGrid<R>::fold(static_cast<int>(floor(grid.coordinate(r.y, 1))), grid.cells.ny);
        const int z = StaggeredGrid<R>::fold(static_cast<int>(floor(grid.coordinate(r.z, 2))), grid.cells.nz);
        return z * grid.cells.ny + y;
    }
};

// Adds scale S v (v: each particle's vector) to one line along x of a field, from the particles whose
// cells lie on lines y - 1 .. y + 2, z - 1 .. z + 2 (the three-point kernel's reach on the staggered
// grid; the grid has at least four cells along each axis, so those lines differ). Each bin in particle
// order: the sum is the same whatever the thread count.
template <class R, class Vectors>
struct InertialFluidSpreadLine {
    const Real4<R>* pos;
    Vectors vectors;
    const int* order;
    const int* lineStart;
    StaggeredGrid<R> grid;
    R scale;
    R* field;

    SMD_HD void operator()(int64_t line) const {
        const FftGrid& g = grid.cells;
        const int64_t points = g.points();
        const int y = static_cast<int>(line % g.ny), z = static_cast<int>(line / g.ny);
        R* row[3] = {field + g.index(0, y, z), field + points + g.index(0, y, z), field + 2 * points + g.index(0, y, z)};
        for (int cz = -1; cz <= 2; ++cz) {
            const int binZ = StaggeredGrid<R>::fold(z + cz, g.nz);
            for (int cy = -1; cy <= 2; ++cy) {
                const int bin = binZ * g.ny + StaggeredGrid<R>::fold(y + cy, g.ny);
                for (int s = lineStart[bin]; s < lineStart[bin + 1]; ++s) {
                    const int i = order[s];
                    const PeskinWeights<R> w(grid, pos[i]);
                    // This line's node among the particle's four along y and z (4 and up: out of reach).
                    const int jy = StaggeredGrid<R>::fold(y - w.first[1], g.ny);
                    const int jz = StaggeredGrid<R>::fold(z - w.first[2], g.nz);
                    if (jy > 3 || jz > 3) continue;
                    const Vec3<R> v = vectors[i];
                    const R value[3] = {scale * v.x, scale * v.y, scale * v.z};
                    for (int c = 0; c < 3; ++c) {
                        const R wyz = w.weight(c, 1, jy) * w.weight(c, 2, jz) * value[c];
                        if (wyz == R(0)) continue;
                        for (int jx = 0; jx < 4; ++jx)
                            row[c][StaggeredGrid<R>::fold(w.first[0] + jx, g.nx)] += wyz * w.weight(c, 0, jx);
                    }
                }
            }
        }
    }
};

// J v: each group member's velocity interpolated from the field (flat, 3i .. 3i + 2); 0 for others.
template <class R>
struct InertialFluidInterpolate {
    const Real4<R>* pos;
    const uint8_t* group;
    StaggeredGrid<R> grid;
    const R* field;
    R* out;

    SMD_HD void operator()(int64_t i) const {
        R sum[3] = {R(0), R(0), R(0)};
        if (!group || group[i]) {
            const FftGrid& g = grid.cells;
            const PeskinWeights<R> w(grid, pos[i]);
            for (int jz = 0; jz < 4; ++jz) {
                const int z = StaggeredGrid<R>::fold(w.first[2] + jz, g.nz);
                for (int jy = 0; jy < 4; ++jy) {
                    const int y = StaggeredGrid<R>::fold(w.first[1] + jy, g.ny);
                    for (int c = 0; c < 3; ++c) {
                        const R wyz = w.weight(c, 1, jy) * w.weight(c, 2, jz);
                        if (wyz == R(0)) continue;
                        const R* line = field + c * g.points() + g.index(0, y, z);
                        for (int jx = 0; jx < 4; ++jx)
                            sum[c] += wyz * w.weight(c, 0, jx) * line[StaggeredGrid<R>::fold(w.first[0] + jx, g.nx)];
                    }
                }
            }
        }
        out[3 * i] = sum[0];
        out[3 * i + 1] = sum[1];
        out[3 * i + 2] = sum[2];
    }
};

// Independent standard normal numbers, `grids` of them per cell, keyed by (stream, cell, step): the
// random stress (six grids: W_xx, W_yy, W_zz at the cell centre, W_xy, W_xz, W_yz at the cell's
// upper edges r + e_a/2 + e_b/2) every step, and the initial fluid velocity (three grids, another
// stream). The step is read from the clock on the backend, so a recorded step graph draws new
// numbers each time it is replayed.
template <class R>
struct DrawStaggeredNormals {
    R* out;       // `grids` grids of cells
    int64_t points;
    int grids;    // at most 8
    uint64_t seed, stream;
    ClockView now;
    SMD_HD void operator()(int64_t cell) const {
        const uint64_t counter = static_cast<uint64_t>(now.step());
        double xi[8];
        normal4(seed, stream ^ static_cast<uint64_t>(2 * cell), counter, xi);
        normal4(seed, stream ^ static_cast<uint64_t>(2 * cell + 1), counter, xi + 4);
        for (int k = 0; k < grids; ++k) out[k * points + cell] = R(xi[k]);
    }
};

// The explicit part of the fluid's step for one cell (eq. 36 of Balboa Usabiaga et al. 2014, m_e = 0),
// divided by rho / dt:
//   g = v + (dt eta / (2 rho)) L v + (sqrt(2 kT eta dt / dV) / rho) D W
//       - (dt / rho) (3/2 A^n - 1/2 A^{n-1}),
// A = D (rho v v^T) the advection in the staggered conservative form (fluxes at cell centres for the
// diagonal, at edges for the rest), second order in time by Adams-Bashforth. The diagonal of the
// random stress carries sqrt(2): then the projected noise has covariance -L P, so that the
// Crank-Nicolson step keeps each mode's variance at kT / (rho dV) exactly. advection holds A^{n-1}
// on entry (firstStep: unused, A^n taken instead) and A^n on exit.
template <class R>
struct StaggeredFluidForcing {
    const R* vel;
    const R* stress;  // six grids; null: no noise
    R* advection;
    R* rhs;
    StaggeredGrid<R> grid;
    R viscousScale;    // dt eta / (2 rho)
    R noiseScale;      // sqrt(2 kT eta dt / dV) / rho
    R advectionScale;  // dt / rho
    R density;
    bool firstStep;

    SMD_HD SMD_INLINE R v(int c, int x, int y, int z, const int* d) const {
        return vel[c * grid.cells.points() + grid.at(x, y, z, d[0], d[1], d[2])];
    }

    SMD_HD void operator()(int64_t cell) const {
        const FftGrid& g = grid.cells;
        const int64_t points = g.points();
        const int x = static_cast<int>(cell % g.nx), y = static_cast<int>((cell / g.nx) % g.ny),
                  z = static_cast<int>(cell / (int64_t(g.nx) * g.ny));
        const int zero[3] = {0, 0, 0};
        const R sqrt2 = R(1.4142135623730951);
        for (int a = 0; a < 3; ++a) {
            const R va = vel[a * points + cell];
            R laplacian = R(0), flux = R(0), noise = R(0);
            for (int b = 0; b < 3; ++b) {
                int up[3] = {0, 0, 0}, down[3] = {0, 0, 0};
                up[b] = 1;
                down[b] = -1;
                const R hb = grid.h(b), inv = R(1) / hb;
                laplacian += (v(a, x, y, z, up) - R(2) * va + v(a, x, y, z, down)) * inv * inv;
                if (b == a) {
                    const R centreUp = R(0.5) * (va + v(a, x, y, z, up)), centreDown = R(0.5) * (va + v(a, x, y, z, down));
                    flux += (centreUp * centreUp - centreDown * centreDown) * inv;
                    if (stress) {
                        const int64_t i = grid.at(x, y, z, up[0], up[1], up[2]);
                        noise += sqrt2 * (stress[a * points + i] - stress[a * points + cell]) * inv;
                    }
                } else {
                    // Edges r + e_a/2 +- e_b/2: v_a averaged along b, v_b averaged along a.
                    int alongA[3] = {0, 0, 0}, alongADown[3] = {0, 0, 0};
                    alongA[a] = 1;
                    alongADown[a] = 1;
                    alongADown[b] = -1;
                    const R edgeUp = R(0.25) * (va + v(a, x, y, z, up)) * (v(b, x, y, z, zero) + v(b, x, y, z, alongA));
                    const R edgeDown =
                        R(0.25) * (v(a, x, y, z, down) + va) * (v(b, x, y, z, down) + v(b, x, y, z, alongADown));
                    flux += (edgeUp - edgeDown) * inv;
                    if (stress) {
                        const int pair = a + b == 1 ? 3 : a + b == 2 ? 4 : 5;  // xy, xz, yz
                        const int64_t below = grid.at(x, y, z, down[0], down[1], down[2]);
                        noise += (stress[pair * points + cell] - stress[pair * points + below]) * inv;
                    }
                }
            }
            const R current = density * flux;
            const R previous = firstStep ? current : advection[a * points + cell];
            advection[a * points + cell] = current;
            rhs[a * points + cell] = va + viscousScale * laplacian + noiseScale * noise -
                                     advectionScale * (R(1.5) * current - R(0.5) * previous);
        }
    }
};

// One wave vector of the half spectrum of a field (three spectra, one after the other): the
// Crank-Nicolson solve and the projection,
//   v_k = P_k g_k / (1 + viscousScale |D|^2) / N,
// N the grid's points (the transforms are unnormalised). The mean (k = 0) is removed or kept.
template <class R>
struct InertialFluidSolve {
    Complex<R>* spectrum;
    StaggeredGrid<R> grid;
    R viscousScale;  // dt eta / (2 rho); 0: the projection alone
    bool removeMean;

    SMD_HD void operator()(int64_t at) const {
        const FftGrid& g = grid.cells;
        const int hx = g.half_x();
        const int64_t spectrumPoints = g.spectrum_points();
        const R inverseN = R(1) / R(g.points());
        Complex<R>* f[3] = {spectrum + at, spectrum + at + spectrumPoints, spectrum + at + 2 * spectrumPoints};
        if (at == 0) {
            for (int c = 0; c < 3; ++c)
                *f[c] = removeMean ? Complex<R>{R(0), R(0)} : Complex<R>{f[c]->re * inverseN, f[c]->im * inverseN};
            return;
        }
        const int m[3] = {static_cast<int>(at % hx), static_cast<int>((at / hx) % g.ny),
                          static_cast<int>(at / (int64_t(hx) * g.ny))};
        const R twoPi = R(6.283185307179586);
        Complex<R> D[3];
        R norm2 = R(0);
        for (int d = 0; d < 3; ++d) {
            const R theta = twoPi * R(m[d]) / R(grid.size(d));
            D[d] = Complex<R>{R((R(1) - cos(theta)) / grid.h(d)), R(sin(theta) / grid.h(d))};
            norm2 += D[d].re * D[d].re + D[d].im * D[d].im;
        }
        // s = D . g
        R sr = R(0), si = R(0);
        for (int d = 0; d < 3; ++d) {
            sr += D[d].re * f[d]->re - D[d].im * f[d]->im;
            si += D[d].re * f[d]->im + D[d].im * f[d]->re;
        }
        const R factor = inverseN / (R(1) + viscousScale * norm2);
        sr /= norm2;
        si /= norm2;
        for (int c = 0; c < 3; ++c) {
            // g - conj(D_c) s
            const R re = f[c]->re - (D[c].re * sr + D[c].im * si);
            const R im = f[c]->im - (D[c].re * si - D[c].im * sr);
            *f[c] = Complex<R>{factor * re, factor * im};
        }
    }
};

}  // namespace structmd
