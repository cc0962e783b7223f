#pragma once
// The Stokes solve of the doubly periodic slab (["BDHIDoublyPeriodic","DPStokes"]): for one wave
// vector k = (kx, ky) of the plane, the force density's transform f_k(z) on the uniform z nodes
// z_j = -H/2 + j hz becomes the velocity's,
//   u_k(z_i) = sum_j hz G_k(z_i, z_j) f_k(z_j),
// G_k the Stokes Green's function in mixed Fourier (x, y) / real (z) form: the unbounded fluid's
// part, plus, where there are walls, the solution of the homogeneous Stokes equations that brings
// the velocity at each no-slip wall to zero.
//
// The unbounded part is the 3D Oseen tensor (I - q q^T / q^2) / (eta q^2) transformed back over q_z
// (kappa = |k|, s = z - z', l along k, t across it). Exactly, e = exp(-kappa |s|),
//   G_tt = e / (2 eta kappa),  G_ll = e (1 - kappa |s|) / (4 eta kappa),
//   G_zz = e (1 + kappa |s|) / (4 eta kappa),  G_lz = G_zl = -i s e / (4 eta);
// G_tt and G_ll have a kink at s = 0, which the sum over nodes would integrate with an error of
// (kappa hz)^2 (the sampled kernel's spectrum aliased). The nodes take instead the kernel band-
// limited to |q_z| < pi / hz (SlabKernelTable: the q_z integral over the band, numerically), whose
// samples carry its spectrum exactly: the only error left is the Gaussians' own aliasing, below
// 1e-5 for hz <= 2 sigma. The wall solutions are smooth and are taken from the exact kernel
// (transverse: exp(-+kappa z); along k and z: (A + B z) exp(-+kappa z), with u_l = i u_z' / kappa
// from incompressibility); both parts are symmetric, so the discrete operator is too.
// k = 0 (the mean flow of the plane): no walls, none (UAMMD's choice: no net flow); a bottom wall,
// eta u'' = -f with u = 0 at the wall and u' = 0 above the forces (the fluid above moves as a plug);
// a slit, u = 0 at both walls. The mean vertical velocity is zero. Its kernels' kink -|z - z'|/2 is
// band-limited as above.
// The Nyquist lines of x and y are left out, as the other grid methods do.
//
// All of it runs in double whatever the working precision (only the spectra are in R): for small
// kappa H the unbounded part is of order 1 / kappa and the walls' part cancels it down to the
// slit's velocity, of order H (transverse) to kappa^2 H^3 (vertical), and the slit's 4 x 4 system
// is nearly singular (its exponentials tend to 1); single precision would lose the result.
#include <cmath>
#include <cstdint>

#include "core/fft_grid.hpp"
#include "core/hd.hpp"
#include "core/lanes.hpp"

namespace structmd {

// The walls, in the order of the "mode" text option.
enum class SlabWalls : int { none = 0, bottom = 1, slit = 2 };

using Complex64 = Complex<double>;

struct SlabColumn {
    Complex64 l, t, z;  // along k, across k, vertical
};

SMD_HD SMD_INLINE Complex64 operator*(double c, Complex64 a) { return {c * a.re, c * a.im}; }
SMD_HD SMD_INLINE Complex64 operator+(Complex64 a, Complex64 b) { return {a.re + b.re, a.im + b.im}; }
SMD_HD SMD_INLINE Complex64 times_i(Complex64 a) { return {-a.im, a.re}; }

// Solves the 4 x 4 system m x = b (real matrix, complex right side) by Gaussian elimination with
// partial pivoting; m and b are overwritten.
SMD_HD SMD_INLINE void solve4(double m[4][4], Complex64 b[4], Complex64 x[4]) {
    for (int c = 0; c < 4; ++c) {
        int pivot = c;
        for (int r = c + 1; r < 4; ++r)
            if (fabs(m[r][c]) > fabs(m[pivot][c])) pivot = r;
        for (int k = 0; k < 4; ++k) {
            const double swap = m[c][k];
            m[c][k] = m[pivot][k];
            m[pivot][k] = swap;
        }
        const Complex64 swap = b[c];
        b[c] = b[pivot];
        b[pivot] = swap;
        for (int r = c + 1; r < 4; ++r) {
            const double factor = m[r][c] / m[c][c];
            for (int k = c; k < 4; ++k) m[r][k] -= factor * m[c][k];
            b[r] = b[r] + (-factor) * b[c];
        }
    }
    for (int r = 3; r >= 0; --r) {
        Complex64 sum = b[r];
        for (int k = r + 1; k < 4; ++k) sum = sum + (-m[r][k]) * x[k];
        x[r] = (1.0 / m[r][r]) * sum;
    }
}

// The wave vector of index `at` of the half spectrum (x fastest, then y); false on the Nyquist
// lines and at k = 0.
SMD_HD SMD_INLINE bool slab_wave_vector(const FftGrid& grid, int64_t at, double lengthX, double lengthY, double& kx,
                                        double& ky) {
    const int hx = grid.half_x();
    const int x = static_cast<int>(at % hx), y = static_cast<int>(at / hx);
    if (2 * x == grid.nx || 2 * y == grid.ny || at == 0) return false;
    const double twoPi = 6.283185307179586;
    kx = twoPi * x / lengthX;
    ky = twoPi * (2 * y < grid.ny ? y : y - grid.ny) / lengthY;
    return true;
}

// One entry of SlabKernelTable. Aligned to its size so that the solve, which reads an entry for each
// of its nz^2 terms, loads it in two 16-byte loads instead of four 8-byte ones.
struct alignas(4 * sizeof(double)) SlabKernelEntry {
    double tt, ll, zz, lz;  // G_tt, G_ll, G_zz, G_lz / -i, times eta; at k = 0, tt is the mean flow's kink
};

// The unbounded kernel band-limited to |q_z| < pi / hz at s = n hz, times eta, for every wave
// vector and n: (G_tt, G_ll, G_zz, G_lz / -i), each (1/pi) int_0^Q of
//   cos(q s) / d,  cos(q s) q^2 / d^2,  cos(q s) kappa^2 / d^2,  kappa q sin(q s) / d^2   (d = kappa^2 + q^2)
// by Simpson's rule on as many intervals as the entry needs: cos(q s) turns n / 2 times over the
// band and 1 / d is kappa wide, so kIntervalsPerTurn intervals per half turn and per width, and two
// more, keep every entry within 6e-7 of the kernel's size at s = 0 (measured against 2^20
// intervals, for Q / kappa from 1 to 512 and n to 3000); a fixed count would alias the tall grids'
// large n. cos(q s) and sin(q s) advance by one rotation a step. An entry costs O(n + Q / kappa),
// the table about as much as a few products of the mesh (whose solve also costs nz^2 a wave
// vector). Computed once per grid.
struct SlabKernelTable {
    FftGrid grid;
    double lengthX, lengthY;
    double zSpacing;
    SlabKernelEntry* table;  // per (wave vector, n), n fastest

    static constexpr double kIntervalsPerTurn = 8.0;

    SMD_HD void operator()(int64_t index) const {
        const int64_t at = index / grid.nz, n = index % grid.nz;
        const double s = zSpacing * double(n);
        SlabKernelEntry& out = table[index];
        out = {0.0, 0.0, 0.0, 0.0};
        if (at == 0) {
            out.tt = band_limited_kink(n);
            return;
        }
        double kx, ky;
        if (!slab_wave_vector(grid, at, lengthX, lengthY, kx, ky)) return;
        const double k2 = kx * kx + ky * ky, kappa = sqrt(k2);
        const double band = 3.141592653589793 / zSpacing;
        const int64_t intervals = 2 * static_cast<int64_t>(ceil(0.5 * kIntervalsPerTurn * (double(n) + band / kappa + 2.0)));
        const double step = band / double(intervals);
        const double turnCos = cos(step * s), turnSin = sin(step * s);
        double c = 1.0, sn = 0.0;  // cos(q s), sin(q s)
        double sum[4] = {0, 0, 0, 0};
        for (int64_t m = 0; m <= intervals; ++m) {
            const double q = step * double(m), d = k2 + q * q;
            const double weight = (m == 0 || m == intervals) ? 1.0 : (m % 2 ? 4.0 : 2.0);
            sum[0] += weight * c / d;
            sum[1] += weight * c * q * q / (d * d);
            sum[2] += weight * c * k2 / (d * d);
            sum[3] += weight * kappa * q * sn / (d * d);
            const double next = c * turnCos - sn * turnSin;
            sn = sn * turnCos + c * turnSin;
            c = next;
        }
        const double norm = step / 3.0 / 3.141592653589793;
        out = {sum[0] * norm, sum[1] * norm, sum[2] * norm, sum[3] * norm};
    }

    // The kink -|s|/2 of the mean flow's kernel band-limited likewise, at s = n hz:
    // (1/pi) f.p. int_0^Q cos(q s) / q^2 dq = -(-1)^n hz / pi^2 - n hz Si(n pi) / pi.
    SMD_HD double band_limited_kink(int64_t n) const {
        const double pi = 3.141592653589793;
        const int intervals = 64 * static_cast<int>(n > 0 ? n : 1);
        const double step = pi * double(n) / intervals;
        double si = 0.0;  // Si(n pi) by Simpson's rule; sin t / t is 1 at t = 0
        for (int m = 0; m <= intervals && n > 0; ++m) {
            const double t = step * m, f = m == 0 ? 1.0 : sin(t) / t;
            si += ((m == 0 || m == intervals) ? 1.0 : (m % 2 ? 4.0 : 2.0)) * f;
        }
        si *= step / 3.0;
        return -(n % 2 ? -1.0 : 1.0) * zSpacing / (pi * pi) - double(n) * zSpacing * si / pi;
    }
};

// The homogeneous Stokes solution of one wave vector that cancels the unbounded fluid's velocity
// at the walls: transverse p exp(-kappa s_a) + r exp(-kappa s_b); along k and z
// u_z = (A + B s_a) exp(-kappa s_a) + (C + D s_b) exp(-kappa s_b), s_a = z - a and s_b = b - z the
// heights above the bottom wall a and below the top one b, u_l = i u_z' / kappa.
struct SlabWallSolution {
    SlabWalls walls;
    double kappa, height;
    Complex64 p{0, 0}, r{0, 0}, coefficient[4] = {};

    // bottom and top: the unbounded fluid's velocity at the walls (top unused without a top wall).
    SMD_HD SlabWallSolution(SlabWalls walls, double kappa, double height, const SlabColumn& bottom, const SlabColumn& top)
        : walls(walls), kappa(kappa), height(height) {
        if (walls == SlabWalls::bottom) {
            p = -1.0 * bottom.t;
            coefficient[0] = -1.0 * bottom.z;
            coefficient[1] = kappa * coefficient[0] + kappa * times_i(bottom.l);
        } else if (walls == SlabWalls::slit) {
            const double e = exp(-kappa * height), kh = kappa * height;
            const double d = 1.0 / (-expm1(-2.0 * kh));  // 1 / (1 - e^2) without the cancellation
            p = d * (-1.0 * bottom.t + e * top.t);
            r = d * (-1.0 * top.t + e * bottom.t);
            double m[4][4] = {{1.0, 0.0, e, height * e},
                              {-kappa, 1.0, kappa * e, (kh - 1.0) * e},
                              {e, height * e, 1.0, 0.0},
                              {-kappa * e, (1.0 - kh) * e, kappa, -1.0}};
            Complex64 rhs[4] = {-1.0 * bottom.z, kappa * times_i(bottom.l), -1.0 * top.z, kappa * times_i(top.l)};
            solve4(m, rhs, coefficient);
        }
    }

    // Its velocity at height sa above the bottom wall.
    SMD_HD SlabColumn at(double sa) const {
        const double sb = height - sa;
        const double ea = exp(-kappa * sa), eb = walls == SlabWalls::slit ? exp(-kappa * sb) : 0.0;
        const Complex64 A = coefficient[0], B = coefficient[1], C = coefficient[2], D = coefficient[3];
        const Complex64 slope = ea * (B + (-kappa) * (A + sa * B)) + eb * (-1.0 * D + kappa * (C + sb * D));
        return {(1.0 / kappa) * times_i(slope), ea * p + eb * r, ea * (A + sa * B) + eb * (C + sb * D)};
    }
};

SMD_HD SMD_INLINE SlabColumn operator+(const SlabColumn& a, const SlabColumn& b) {
    return {a.l + b.l, a.t + b.t, a.z + b.z};
}

// A column's sum over an item's lanes (Lanes::combine, the fixed butterfly of Lanes::sum).
SMD_HD SMD_INLINE SlabColumn lanes_sum(const Lanes& lanes, const SlabColumn& c) {
    return lanes.combine(c, [](SlabColumn& total, const SlabColumn& other) { total = total + other; });
}

// One wave vector of the half spectrum (x fastest, then y), all its z nodes. The spectra hold the
// three components one after the other, each nz planes of (nx/2 + 1) ny numbers. The item's lanes
// share out its work: the unbounded fluid's velocity at the walls over the nodes j (lane,
// lane + count, ...), summed across them, and then the nodes i likewise, each lane a row of the
// nz x nz convolution (one lane does everything in the order of the loops). A thread per wave
// vector, some 10^4 of them, each nz^2 terms long, left the device mostly idle.
template <class R>
struct SlabStokesSolve {
    const Complex<R>* force;
    Complex<R>* velocity;
    const SlabKernelEntry* kernel;  // SlabKernelTable's
    FftGrid grid;                   // nz: the z nodes
    double lengthX, lengthY;        // the periodic box
    double zSpacing;                // hz = H / (nz - 1)
    double scale;                   // hz / (nx ny eta): the quadrature weight, the transforms' norm, the viscosity
    SlabWalls walls;

    // Its doubles need more than the default launch's 64 registers: under that cap 35% of its memory
    // requests were spills (Nsight Compute); at 5 blocks (96 registers) none are, and the solve at
    // 150 x 150 x 30 ran 10% faster in single precision, 17% in double (docs/benchmarks.md).
    static constexpr int kResidentBlocks = 5;

    SMD_HD void operator()(int64_t at, Lanes lanes) const {
        const int hx = grid.half_x();
        const int64_t plane = int64_t(hx) * grid.ny, component = plane * grid.nz;
        const int x = static_cast<int>(at % hx), y = static_cast<int>(at / hx);
        if (2 * x == grid.nx || 2 * y == grid.ny) {
            for (int i = lanes.lane; i < grid.nz; i += lanes.count)
                for (int c = 0; c < 3; ++c) velocity[at + i * plane + c * component] = Complex<R>{R(0), R(0)};
            return;
        }
        if (at == 0) {
            for (int i = lanes.lane; i < grid.nz; i += lanes.count) mean_flow(i, plane, component);
            return;
        }
        double kx, ky;
        slab_wave_vector(grid, at, lengthX, lengthY, kx, ky);
        const double kappa = sqrt(kx * kx + ky * ky);
        const double ux = kx / kappa, uy = ky / kappa;
        SlabColumn bottom{}, top{};
        if (walls != SlabWalls::none) bottom = lanes_sum(lanes, wall_velocity(at, 0, plane, component, kappa, ux, uy, lanes));
        if (walls == SlabWalls::slit)
            top = lanes_sum(lanes, wall_velocity(at, grid.nz - 1, plane, component, kappa, ux, uy, lanes));
        const SlabWallSolution wall(walls, kappa, zSpacing * (grid.nz - 1), bottom, top);
        for (int i = lanes.lane; i < grid.nz; i += lanes.count) {
            SlabColumn u = banded_velocity(at, i, plane, component, ux, uy);
            if (walls != SlabWalls::none) u = u + wall.at(zSpacing * i);
            const int64_t node = at + i * plane;
            velocity[node] = narrowed(ux * u.l + (-uy) * u.t);
            velocity[node + component] = narrowed(uy * u.l + ux * u.t);
            velocity[node + 2 * component] = narrowed(u.z);
        }
    }

private:
    SMD_HD static Complex64 widened(Complex<R> a) { return {double(a.re), double(a.im)}; }
    SMD_HD static Complex<R> narrowed(Complex64 a) { return {R(a.re), R(a.im)}; }

    // The force at node j in the (l, t, z) frame.
    SMD_HD SlabColumn force_at(int64_t node, int64_t component, double ux, double uy) const {
        const Complex64 fx = widened(force[node]), fy = widened(force[node + component]);
        return {ux * fx + uy * fy, (-uy) * fx + ux * fy, widened(force[node + 2 * component])};
    }

    // The unbounded fluid's velocity at node i (l, t, z components) by the band-limited kernel, scaled.
    SMD_HD SlabColumn banded_velocity(int64_t at, int i, int64_t plane, int64_t component, double ux, double uy) const {
        SlabColumn u{};
        const SlabKernelEntry* row = kernel + at * grid.nz;
        for (int j = 0; j < grid.nz; ++j) {
            const SlabColumn f = force_at(at + j * plane, component, ux, uy);
            const SlabKernelEntry g = row[i < j ? j - i : i - j];
            const double lz = i < j ? g.lz : -g.lz;  // G_lz / i = -g.lz sign(s), s = z_i - z_j
            u.t = u.t + g.tt * f.t;
            u.l = u.l + g.ll * f.l + lz * times_i(f.z);
            u.z = u.z + g.zz * f.z + lz * times_i(f.l);
        }
        return {scale * u.l, scale * u.t, scale * u.z};
    }

    // This lane's part of the unbounded fluid's velocity at a wall (node 0 or nz - 1) by the exact
    // kernel, scaled: the nodes lane, lane + count, ... away from it. The forces lie on one side of
    // the wall, where the exact kernel is smooth and what the wall solution cancels.
    // exp(-kappa |s|) is carried along from the wall inwards, a factor exp(-kappa hz count) a term.
    SMD_HD SlabColumn wall_velocity(int64_t at, int wall, int64_t plane, int64_t component, double kappa, double ux,
                                    double uy, const Lanes& lanes) const {
        SlabColumn u{};
        const double inverseKappa = 1.0 / kappa, q = exp(-kappa * zSpacing * lanes.count);
        double e = exp(-kappa * zSpacing * lanes.lane);
        for (int distance = lanes.lane; distance < grid.nz; distance += lanes.count, e *= q) {
            const int j = wall == 0 ? distance : wall - distance;
            const SlabColumn f = force_at(at + j * plane, component, ux, uy);
            const double s = zSpacing * (wall - j), ks = kappa * fabs(s);
            const double ll = e * (1.0 - ks) * inverseKappa * 0.25, zz = e * (1.0 + ks) * inverseKappa * 0.25;
            const double lz = -0.25 * s * e;  // G_lz / i
            u.l = u.l + ll * f.l + lz * times_i(f.z);
            u.z = u.z + zz * f.z + lz * times_i(f.l);
            u.t = u.t + (0.5 * e * inverseKappa) * f.t;
        }
        return {scale * u.l, scale * u.t, scale * u.z};
    }

    // k = 0: the mean flow of the plane at node i (see the header).
    SMD_HD void mean_flow(int i, int64_t plane, int64_t component) const {
        const double height = zSpacing * (grid.nz - 1);
        Complex64 ux{0, 0}, uy{0, 0};
        if (walls != SlabWalls::none)
            for (int j = 0; j < grid.nz; ++j) {
                // min(z, z') (bottom) and min (H - max) / H (slit), heights from the bottom
                // wall, as their smooth parts plus the band-limited kink -|s|/2.
                const double middle = 0.5 * zSpacing * (i + j), s = zSpacing * (i - j);
                const double smooth = walls == SlabWalls::bottom ? middle : (middle * (height - middle) + 0.25 * s * s) / height;
                const double g = smooth + kernel[i < j ? j - i : i - j].tt;
                ux = ux + (scale * g) * widened(force[j * plane]);
                uy = uy + (scale * g) * widened(force[j * plane + component]);
            }
        velocity[i * plane] = narrowed(ux);
        velocity[i * plane + component] = narrowed(uy);
        velocity[i * plane + 2 * component] = Complex<R>{R(0), R(0)};
    }
};

}  // namespace structmd
