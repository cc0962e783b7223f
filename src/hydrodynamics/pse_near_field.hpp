#pragma once
// The real-space (near-field) part of the positively split Ewald sum of the Rotne-Prager-Yamakawa
// mobility of equal spheres of radius a (Fiore, Balboa Usabiaga, Donev & Swan, J. Chem. Phys. 146,
// 124116 (2017), appendix A): with splitting xi,
//   M_near(r) = mu0 [F(r) (I - r^ r^) + G(r) r^ r^],   mu0 = 1 / (6 pi eta a),
// the free-space RPY tensor (its overlapping form below r = 2a) less the real-space image of the
// far field's multiplier (pse_far_field.hpp). F and G are sums of polynomials in r times
// exp(-xi^2 r^2), exp(-xi^2 (r -+ 2a)^2), erfc(xi r) and erfc(xi (r -+ 2a)); the slowest terms fall
// as exp(-xi^2 (r - 2a)^2), and the sum is cut where that reaches the tolerance,
// r_c = 2a + sqrt(-ln tol) / xi: beyond it |F|, |G| < tol / 20 for tol in [1e-10, 0.1] and xi a in
// [0.05, 10]. (UAMMD cuts at sqrt(-ln tol) / xi, where they are still 1 to 30 tol.) The self block is F(0) I,
//   F(0) = [1 - exp(-4 a^2 xi^2) + 4 sqrt(pi) a xi erfc(2 a xi)] / (4 sqrt(pi) a xi).
// M_near is positive definite (the split's point), so its square root exists.
//
// Evaluated in double whatever the precision: the terms of F and G grow as a^3 / r^3 and
// 1 / (xi^4 a r^3) towards r = 0 and cancel. Below r_0 = 3e-3 max(a, (a xi^4)^{-1/3}) (at most a) they
// would cancel to rounding, and F, G take their expansion about 0 instead: M_near = RPY - (far part),
// RPY linear in r inside 2a and the far part smooth and even, so
//   F = F(0) - 9 r / (32 a) + (2/15) c r^2,   G = F(0) - 3 r / (16 a) + (1/15) c r^2,
//   c = 3 xi / (4 sqrt(pi) a) (3 - 3 E + 8 a^2 xi^2 E),   E = exp(-4 a^2 xi^2)
// (c from the far part's Taylor series: its multiplier's fourth moment). Either side of r_0 the
// error is below 3e-7 of F(0) for xi a in [0.02, 5] (checked against 50-digit arithmetic).
#include <cmath>

#include "core/vec.hpp"

namespace structmd {

template <class R>
struct PseNearTensor {
    double radius;         // a
    double xi;             // the splitting
    double mobility;       // mu0 = 1 / (6 pi eta a)
    double cutoff2;        // r_c^2
    double selfTransverse; // F(0)
    double smallDistance;  // r_0
    double curvature;      // c

    // (F, G) at r > 0 (dimensionless: times mu0 they are the mobility).
    SMD_HD SMD_INLINE Vec3<double> coefficients(double r) const {
        const double a = radius;
        if (r < smallDistance)
            return {selfTransverse - 9.0 * r / (32.0 * a) + (2.0 / 15.0) * curvature * r * r,
                    selfTransverse - 3.0 * r / (16.0 * a) + (1.0 / 15.0) * curvature * r * r, 0.0};
        const double rootPi = 1.7724538509055160273;
        const double x2 = xi * xi, x3 = x2 * xi, x4 = x2 * x2;
        const double r2 = r * r, r3 = r2 * r, r4 = r2 * r2, a2 = a * a, a4 = a2 * a2;
        const double plus = r + 2.0 * a, minus = 2.0 * a - r;  // r + 2a and 2a - r
        const double gaussPlus = exp(-x2 * plus * plus), gaussMinus = exp(-x2 * minus * minus), gauss = exp(-x2 * r2);
        const double erfcPlus = erfc(xi * plus), erfcR = erfc(xi * r);
        const double quarticT = 4.0 * a2 + 4.0 * a * r + 9.0 * r2;  // the transverse polynomials
        const double quarticTPlus = 4.0 * a2 - 4.0 * a * r + 9.0 * r2;
        const double t3 = 128.0 * a * r3, t4 = t3 * x4;  // common denominators
        double f = (-2.0 * x2 * plus * quarticTPlus + 2.0 * a - 3.0 * r) / (t3 * x3 * rootPi) * gaussPlus +
                   (2.0 * x2 * minus * quarticT - 2.0 * a - 3.0 * r) / (t3 * x3 * rootPi) * gaussMinus +
                   3.0 * (6.0 * r2 * x2 + 1.0) / (64.0 * rootPi * a * r2 * x3) * gauss +
                   (4.0 * x4 * plus * plus * quarticTPlus - 3.0) / (2.0 * t4) * erfcPlus +
                   3.0 * (1.0 - 12.0 * r4 * x4) / t4 * erfcR;
        double g = (2.0 * x2 * plus * plus * (2.0 * a - 3.0 * r) - 2.0 * a + 3.0 * r) / (0.5 * t3 * x3 * rootPi) * gaussPlus +
                   (-2.0 * x2 * minus * minus * (2.0 * a + 3.0 * r) + 2.0 * a + 3.0 * r) / (0.5 * t3 * x3 * rootPi) * gaussMinus +
                   3.0 * (2.0 * r2 * x2 - 1.0) / (32.0 * rootPi * a * r2 * x3) * gauss +
                   (3.0 - 4.0 * x4 * (2.0 * a - 3.0 * r) * plus * plus * plus) / t4 * erfcPlus -
                   3.0 * (4.0 * r4 * x4 + 1.0) / (0.5 * t4) * erfcR;
        // The terms in erfc(xi (2a - r)) and the polynomial: RPY's far form outside contact, its
        // overlapping form inside (there erfc(xi (r - 2a)) = 2 - erfc(xi (2a - r))).
        const double erfcMinus = erfc(xi * minus);
        const double transverseMinus = (3.0 - 4.0 * x4 * minus * minus * quarticT) / (2.0 * t4);
        const double longitudinalMinus = (4.0 * x4 * minus * minus * minus * (2.0 * a + 3.0 * r) - 3.0) / t4;
        if (r > 2.0 * a) {
            f += (64.0 * a4 * x4 + 96.0 * a2 * r2 * x4 - 128.0 * a * r3 * x4 + 36.0 * r4 * x4 - 3.0) / t4 +
                 transverseMinus * erfcMinus;
            g += (-64.0 * a4 * x4 + 96.0 * a2 * r2 * x4 - 64.0 * a * r3 * x4 + 12.0 * r4 * x4 + 3.0) / (0.5 * t4) +
                 longitudinalMinus * erfcMinus;
        } else {
            f += (-16.0 * a4 - 24.0 * a2 * r2 + 32.0 * a * r3 - 9.0 * r4) / (32.0 * a * r3) -
                 transverseMinus * (2.0 - erfcMinus);
            g += minus * minus * minus * (2.0 * a + 3.0 * r) / (16.0 * a * r3) - longitudinalMinus * (2.0 - erfcMinus);
        }
        return {f, g, 0.0};
    }

    // M_near(d) v for the separation d, 0 beyond the cutoff. Two particles at one point (d = 0) have
    // the isotropic limit c.x I of the overlapping tensor, not the 0/0 of its r r^T / r^2 term.
    SMD_HD SMD_INLINE Vec3<R> apply(const Vec3<R>& d, const Vec3<R>& v) const {
        const double dx = double(d.x), dy = double(d.y), dz = double(d.z);
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (!(r2 < cutoff2)) return {R(0), R(0), R(0)};
        const double r = sqrt(r2);
        const Vec3<double> c = coefficients(r);
        const double along =
            r2 > 0.0 ? (c.y - c.x) * (dx * double(v.x) + dy * double(v.y) + dz * double(v.z)) / r2 : 0.0;
        return {R(mobility * (c.x * double(v.x) + along * dx)), R(mobility * (c.x * double(v.y) + along * dy)),
                R(mobility * (c.x * double(v.z) + along * dz))};
    }

    SMD_HD SMD_INLINE R self() const { return R(mobility * selfTransverse); }
};

#if SMD_HOST_CODE
inline double pse_near_cutoff(double radius, double xi, double tolerance) {
    return 2.0 * radius + std::sqrt(-std::log(tolerance)) / xi;
}

template <class R>
PseNearTensor<R> make_pse_near_tensor(double radius, double xi, double viscosity, double tolerance) {
    const double pi = M_PI, cutoff = pse_near_cutoff(radius, xi, tolerance);
    const double ax = radius * xi, overlap = std::exp(-4.0 * ax * ax);
    const double self = (1.0 - overlap + 4.0 * std::sqrt(pi) * ax * std::erfc(2.0 * ax)) / (4.0 * std::sqrt(pi) * ax);
    const double small = std::fmin(3e-3 * std::fmax(radius, std::cbrt(1.0 / (radius * xi * xi * xi * xi))), radius);
    const double curvature = 3.0 * xi / (4.0 * std::sqrt(pi) * radius) * (3.0 - 3.0 * overlap + 8.0 * ax * ax * overlap);
    return {radius, xi, 1.0 / (6.0 * pi * viscosity * radius), cutoff * cutoff, self, small, curvature};
}
#endif

}  // namespace structmd
