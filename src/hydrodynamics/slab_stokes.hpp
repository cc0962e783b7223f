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
#include <cmath>
#include <cstdint>

#include "core/fft_grid.hpp"
#include "core/hd.hpp"

namespace structmd {

// The walls, in the order of the "mode" text option.
enum class SlabWalls : int { none = 0, bottom = 1, slit = 2 };

template <class R>
struct SlabColumn {
    Complex<R> l, t, z;  // along k, across k, vertical
};

template <class R>
SMD_HD SMD_INLINE Complex<R> operator*(R c, Complex<R> a) {
    return {c * a.re, c * a.im};
}
template <class R>
SMD_HD SMD_INLINE Complex<R> operator+(Complex<R> a, Complex<R> b) {
    return {a.re + b.re, a.im + b.im};
}
template <class R>
SMD_HD SMD_INLINE Complex<R> times_i(Complex<R> a) {
    return {-a.im, a.re};
}

// Solves the 4 x 4 system m x = b (real matrix, complex right side) by Gaussian elimination with
// partial pivoting; m and b are overwritten.
template <class R>
SMD_HD SMD_INLINE void solve4(R m[4][4], Complex<R> b[4], Complex<R> x[4]) {
    for (int c = 0; c < 4; ++c) {
        int pivot = c;
        for (int r = c + 1; r < 4; ++r)
            if (fabs(m[r][c]) > fabs(m[pivot][c])) pivot = r;
        for (int k = 0; k < 4; ++k) {
            const R swap = m[c][k];
            m[c][k] = m[pivot][k];
            m[pivot][k] = swap;
        }
        const Complex<R> swap = b[c];
        b[c] = b[pivot];
        b[pivot] = swap;
        for (int r = c + 1; r < 4; ++r) {
            const R factor = m[r][c] / m[c][c];
            for (int k = c; k < 4; ++k) m[r][k] -= factor * m[c][k];
            b[r] = b[r] + (-factor) * b[c];
        }
    }
    for (int r = 3; r >= 0; --r) {
        Complex<R> sum = b[r];
        for (int k = r + 1; k < 4; ++k) sum = sum + (-m[r][k]) * x[k];
        x[r] = (R(1) / m[r][r]) * sum;
    }
}

// The wave vector of index `at` of the half spectrum (x fastest, then y); false on the Nyquist
// lines and at k = 0.
template <class R>
SMD_HD SMD_INLINE bool slab_wave_vector(const FftGrid& grid, int64_t at, R lengthX, R lengthY, R& kx, R& ky) {
    const int hx = grid.half_x();
    const int x = static_cast<int>(at % hx), y = static_cast<int>(at / hx);
    if (2 * x == grid.nx || 2 * y == grid.ny || at == 0) return false;
    const R twoPi = R(6.283185307179586);
    kx = twoPi * R(x) / lengthX;
    ky = twoPi * R(2 * y < grid.ny ? y : y - grid.ny) / lengthY;
    return true;
}

// The unbounded kernel band-limited to |q_z| < pi / hz at s = n hz, times eta, for every wave
// vector and n: (G_tt, G_ll, G_zz, G_lz / -i), each (1/pi) int_0^Q of
//   cos(q s) / d,  cos(q s) q^2 / d^2,  cos(q s) kappa^2 / d^2,  kappa q sin(q s) / d^2   (d = kappa^2 + q^2)
// by Simpson's rule (the integrands are smooth; 1024 intervals resolve s up to 160 hz to 1e-6).
// Computed once per grid.
template <class R>
struct SlabKernelTable {
    FftGrid grid;
    R lengthX, lengthY;
    double zSpacing;
    R* table;  // four numbers per (wave vector, n), n fastest

    static constexpr int kIntervals = 1024;

    SMD_HD void operator()(int64_t index) const {
        const int64_t at = index / grid.nz;
        const double s = zSpacing * double(index % grid.nz);
        R* out = table + 4 * index;
        for (int c = 0; c < 4; ++c) out[c] = R(0);
        if (at == 0) {
            out[0] = R(band_limited_kink(index % grid.nz));
            return;
        }
        R kx, ky;
        if (!slab_wave_vector(grid, at, lengthX, lengthY, kx, ky)) return;
        const double k2 = double(kx) * double(kx) + double(ky) * double(ky), kappa = sqrt(k2);
        const double step = 3.141592653589793 / zSpacing / kIntervals;
        double sum[4] = {0, 0, 0, 0};
        for (int m = 0; m <= kIntervals; ++m) {
            const double q = step * m, d = k2 + q * q, c = cos(q * s), sn = sin(q * s);
            const double weight = (m == 0 || m == kIntervals) ? 1.0 : (m % 2 ? 4.0 : 2.0);
            sum[0] += weight * c / d;
            sum[1] += weight * c * q * q / (d * d);
            sum[2] += weight * c * k2 / (d * d);
            sum[3] += weight * kappa * q * sn / (d * d);
        }
        for (int c = 0; c < 4; ++c) out[c] = R(sum[c] * step / 3.0 / 3.141592653589793);
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

// One wave vector of the half spectrum (x fastest, then y), all its z nodes. The spectra hold the
// three components one after the other, each nz planes of (nx/2 + 1) ny numbers.
template <class R>
struct SlabStokesSolve {
    const Complex<R>* force;
    Complex<R>* velocity;
    const R* kernel;     // SlabKernelTable's
    FftGrid grid;        // nz: the z nodes
    R lengthX, lengthY;  // the periodic box
    R zSpacing;          // hz = H / (nz - 1)
    R scale;             // hz / (nx ny eta): the quadrature weight, the transforms' norm, the viscosity
    SlabWalls walls;

    SMD_HD void operator()(int64_t at) const {
        const int hx = grid.half_x();
        const int64_t plane = int64_t(hx) * grid.ny, component = plane * grid.nz;
        const int x = static_cast<int>(at % hx), y = static_cast<int>(at / hx);
        if (2 * x == grid.nx || 2 * y == grid.ny) {
            for (int i = 0; i < grid.nz; ++i)
                for (int c = 0; c < 3; ++c) velocity[at + i * plane + c * component] = Complex<R>{R(0), R(0)};
            return;
        }
        if (at == 0) {
            mean_flow(plane, component);
            return;
        }
        R kx, ky;
        slab_wave_vector(grid, at, lengthX, lengthY, kx, ky);
        const R kappa = sqrt(kx * kx + ky * ky);
        const R ux = kx / kappa, uy = ky / kappa;
        const R q = exp(-kappa * zSpacing);  // exp(-kappa |s|) = q^|i - j|
        SlabColumn<R> bottom{}, top{};
        if (walls != SlabWalls::none) bottom = wall_velocity(at, 0, plane, component, kappa, ux, uy, q);
        if (walls == SlabWalls::slit) top = wall_velocity(at, grid.nz - 1, plane, component, kappa, ux, uy, q);
        const R height = zSpacing * R(grid.nz - 1);
        const R across = exp(-kappa * height);
        // The wall solution's coefficients: transverse p exp(-kappa s_a) + r exp(-kappa s_b), along
        // k and z u_z = (A + B s_a) exp(-kappa s_a) + (C + D s_b) exp(-kappa s_b), s_a = z - a and
        // s_b = b - z the heights above the bottom wall a and below the top one b.
        Complex<R> p{R(0), R(0)}, r{R(0), R(0)}, coefficient[4] = {};
        if (walls == SlabWalls::bottom) {
            p = R(-1) * bottom.t;
            coefficient[0] = R(-1) * bottom.z;
            coefficient[1] = kappa * coefficient[0] + kappa * times_i(bottom.l);
        } else if (walls == SlabWalls::slit) {
            const R d = R(1) / (R(1) - across * across);
            p = d * (R(-1) * bottom.t + across * top.t);
            r = d * (R(-1) * top.t + across * bottom.t);
            const R e = across, kh = kappa * height;
            R m[4][4] = {{R(1), R(0), e, height * e},
                         {-kappa, R(1), kappa * e, (kh - R(1)) * e},
                         {e, height * e, R(1), R(0)},
                         {-kappa * e, (R(1) - kh) * e, kappa, R(-1)}};
            Complex<R> rhs[4] = {R(-1) * bottom.z, kappa * times_i(bottom.l), R(-1) * top.z, kappa * times_i(top.l)};
            solve4(m, rhs, coefficient);
        }
        for (int i = 0; i < grid.nz; ++i) {
            SlabColumn<R> u = banded_velocity(at, i, plane, component, ux, uy);
            if (walls != SlabWalls::none) {
                const R sa = zSpacing * R(i), sb = height - sa;
                const R ea = exp(-kappa * sa), eb = walls == SlabWalls::slit ? exp(-kappa * sb) : R(0);
                const Complex<R> A = coefficient[0], B = coefficient[1], C = coefficient[2], D = coefficient[3];
                u.t = u.t + ea * p + eb * r;
                u.z = u.z + ea * (A + sa * B) + eb * (C + sb * D);
                const Complex<R> slope = ea * (B + (-kappa) * (A + sa * B)) + eb * (R(-1) * D + kappa * (C + sb * D));
                u.l = u.l + (R(1) / kappa) * times_i(slope);
            }
            const int64_t node = at + i * plane;
            velocity[node] = ux * u.l + (-uy) * u.t;
            velocity[node + component] = uy * u.l + ux * u.t;
            velocity[node + 2 * component] = u.z;
        }
    }

private:
    // The unbounded fluid's velocity at node i (l, t, z components) by the band-limited kernel, scaled.
    SMD_HD SlabColumn<R> banded_velocity(int64_t at, int i, int64_t plane, int64_t component, R ux, R uy) const {
        SlabColumn<R> u{};
        const R* row = kernel + 4 * at * grid.nz;
        for (int j = 0; j < grid.nz; ++j) {
            const int64_t node = at + j * plane;
            const Complex<R> fx = force[node], fy = force[node + component], fz = force[node + 2 * component];
            const Complex<R> fl = ux * fx + uy * fy, ft = (-uy) * fx + ux * fy;
            const R* g = row + 4 * (i < j ? j - i : i - j);
            const R lz = i < j ? g[3] : -g[3];  // G_lz / i = -g[3] sign(s), s = z_i - z_j
            u.t = u.t + g[0] * ft;
            u.l = u.l + g[1] * fl + lz * times_i(fz);
            u.z = u.z + g[2] * fz + lz * times_i(fl);
        }
        u.l = scale * u.l;
        u.t = scale * u.t;
        u.z = scale * u.z;
        return u;
    }

    // The unbounded fluid's velocity at a wall (node 0 or nz - 1) by the exact kernel, scaled: the
    // forces lie on one side of it, where the exact kernel is smooth and what the wall solution
    // cancels. exp(-kappa |s|) = q^|i - j| is carried along from the wall inwards.
    SMD_HD SlabColumn<R> wall_velocity(int64_t at, int wall, int64_t plane, int64_t component, R kappa, R ux, R uy,
                                       R q) const {
        SlabColumn<R> u{};
        const R inverseKappa = R(1) / kappa;
        R e = R(1);
        for (int distance = 0; distance < grid.nz; ++distance, e *= q) {
            const int j = wall == 0 ? distance : wall - distance;
            const int64_t node = at + j * plane;
            const Complex<R> fx = force[node], fy = force[node + component], fz = force[node + 2 * component];
            const Complex<R> fl = ux * fx + uy * fy, ft = (-uy) * fx + ux * fy;
            const R s = zSpacing * R(wall - j), ks = kappa * fabs(s);
            const R ll = e * (R(1) - ks) * inverseKappa * R(0.25), zz = e * (R(1) + ks) * inverseKappa * R(0.25);
            const R lz = R(-0.25) * s * e;  // G_lz / i
            u.l = u.l + ll * fl + lz * times_i(fz);
            u.z = u.z + zz * fz + lz * times_i(fl);
            u.t = u.t + (R(0.5) * e * inverseKappa) * ft;
        }
        u.l = scale * u.l;
        u.t = scale * u.t;
        u.z = scale * u.z;
        return u;
    }

    // k = 0: the mean flow of the plane at every height (see the header).
    SMD_HD void mean_flow(int64_t plane, int64_t component) const {
        const R height = zSpacing * R(grid.nz - 1);
        for (int i = 0; i < grid.nz; ++i) {
            Complex<R> ux{R(0), R(0)}, uy{R(0), R(0)};
            if (walls != SlabWalls::none)
                for (int j = 0; j < grid.nz; ++j) {
                    // min(z, z') (bottom) and min (H - max) / H (slit), heights from the bottom
                    // wall, as their smooth parts plus the band-limited kink -|s|/2.
                    const R middle = R(0.5) * zSpacing * R(i + j), s = zSpacing * R(i - j);
                    const R smooth = walls == SlabWalls::bottom ? middle : (middle * (height - middle) + R(0.25) * s * s) / height;
                    const R g = smooth + kernel[4 * (i < j ? j - i : i - j)];
                    ux = ux + (scale * g) * force[j * plane];
                    uy = uy + (scale * g) * force[j * plane + component];
                }
            velocity[i * plane] = ux;
            velocity[i * plane + component] = uy;
            velocity[i * plane + 2 * component] = Complex<R>{R(0), R(0)};
        }
    }
};

}  // namespace structmd
