#pragma once
// The Rotne-Prager-Yamakawa mobility of two spheres in an unbounded fluid of viscosity eta, in the
// form for unequal radii a_i, a_j of Zuk, Wajnryb, Mizerski and Szymczak (J. Fluid Mech. 741, R5,
// 2014; for equal radii it is Rotne & Prager 1969 and, overlapping, Wajnryb et al. 2013):
//   M_ij = f(r) I + g(r) r^ r^, with r = |r_j - r_i| and
//   r > a_i + a_j:           f = (1 + (a_i^2 + a_j^2) / (3 r^2)) / (8 pi eta r),
//                            g = (1 - (a_i^2 + a_j^2) / r^2) / (8 pi eta r)
//   |a_i - a_j| < r <= a_i + a_j (overlapping):
//                            f = [16 r^3 (a_i + a_j) - ((a_i - a_j)^2 + 3 r^2)^2] / (32 r^3) / (6 pi eta a_i a_j),
//                            g = 3 ((a_i - a_j)^2 - r^2)^2 / (32 r^3) / (6 pi eta a_i a_j)
//   r <= |a_i - a_j| (one inside the other, and the self block r = 0):
//                            f = 1 / (6 pi eta max(a_i, a_j)), g = 0.
// The tensor is continuous across both radii and positive definite for any configuration, which the
// square root of the noise needs.
#include "core/vec.hpp"

namespace structmd {

template <class R>
struct RpyCoefficients {
    R f, g;  // M = f I + g r^ r^
};

template <class R>
struct RpyTensor {
    R inverseViscosity;  // 1 / eta

    SMD_HD SMD_INLINE RpyCoefficients<R> coefficients(R r, R ai, R aj) const {
        const R pi = R(3.14159265358979323846);
        const R sumRadii = ai + aj;
        const R difference = ai > aj ? ai - aj : aj - ai;
        if (r > sumRadii) {
            const R prefactor = inverseViscosity / (R(8) * pi * r);
            const R squares = (ai * ai + aj * aj) / (r * r);
            return {prefactor * (R(1) + squares / R(3)), prefactor * (R(1) - squares)};
        }
        if (r > difference) {
            const R prefactor = inverseViscosity / (R(6) * pi * ai * aj * R(32) * r * r * r);
            const R d2 = difference * difference;
            const R inner = d2 + R(3) * r * r;
            const R outer = d2 - r * r;
            return {prefactor * (R(16) * r * r * r * sumRadii - inner * inner), prefactor * R(3) * outer * outer};
        }
        return {inverseViscosity / (R(6) * pi * (ai > aj ? ai : aj)), R(0)};
    }

    // M_ij v for the separation d = r_j - r_i.
    SMD_HD SMD_INLINE Vec3<R> apply(const Vec3<R>& d, R ai, R aj, const Vec3<R>& v) const {
        const R r = sqrt(dot(d, d));
        const RpyCoefficients<R> c = coefficients(r, ai, aj);
        Vec3<R> out = c.f * v;
        if (c.g != R(0)) out += (c.g * dot(d, v) / (r * r)) * d;
        return out;
    }

    // Entry (a, b) of M_ij for the separation d = r_j - r_i.
    SMD_HD SMD_INLINE R entry(const Vec3<R>& d, R ai, R aj, int a, int b) const {
        const R r = sqrt(dot(d, d));
        const RpyCoefficients<R> c = coefficients(r, ai, aj);
        const R component[3] = {d.x, d.y, d.z};
        return (a == b ? c.f : R(0)) + (c.g != R(0) ? c.g * component[a] * component[b] / (r * r) : R(0));
    }
};

}  // namespace structmd
