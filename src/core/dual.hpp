#pragma once
// Dual numbers for forward-mode differentiation: Dual{v, d} carries a value and its derivative with
// respect to one chosen variable, and every operation applies the chain rule. A potential written
// once for a real type R, instantiated with Dual<R>, gives exact derivatives of whatever it
// computes (its forces, hence the Hessian) with no second formula to keep in step with the first.
//
// The math functions are hidden friends, found only by argument-dependent lookup: the unqualified
// sqrt(x) of a potential picks them for a Dual and the ordinary ones for a float or double.
// Comparisons and rounding look at the value alone (a branch is taken as at the value; rounding has
// zero derivative almost everywhere).
#include "core/hd.hpp"
#include "core/real_limits.hpp"
#if SMD_HOST_CODE
#include <cmath>
#include <limits>
#include <type_traits>
#endif

namespace structmd {

template <class R>
struct Dual {
    R v;  // the value
    R d;  // its derivative

    Dual() = default;
    template <class T, class = std::enable_if_t<std::is_arithmetic_v<T>>>
    SMD_HD constexpr Dual(T value) : v(R(value)), d(R(0)) {}
    SMD_HD constexpr Dual(R value, R derivative) : v(value), d(derivative) {}

    SMD_HD explicit operator int() const { return static_cast<int>(v); }

    SMD_HD Dual& operator+=(Dual b) { v += b.v; d += b.d; return *this; }
    SMD_HD Dual& operator-=(Dual b) { v -= b.v; d -= b.d; return *this; }
    SMD_HD Dual& operator*=(Dual b) { *this = *this * b; return *this; }
    SMD_HD Dual& operator/=(Dual b) { *this = *this / b; return *this; }

    friend SMD_HD SMD_INLINE Dual operator+(Dual a) { return a; }
    friend SMD_HD SMD_INLINE Dual operator-(Dual a) { return Dual(-a.v, -a.d); }
    friend SMD_HD SMD_INLINE Dual operator+(Dual a, Dual b) { return Dual(a.v + b.v, a.d + b.d); }
    friend SMD_HD SMD_INLINE Dual operator-(Dual a, Dual b) { return Dual(a.v - b.v, a.d - b.d); }
    friend SMD_HD SMD_INLINE Dual operator*(Dual a, Dual b) { return Dual(a.v * b.v, a.d * b.v + a.v * b.d); }
    friend SMD_HD SMD_INLINE Dual operator/(Dual a, Dual b) {
        const R q = a.v / b.v;
        return Dual(q, (a.d - q * b.d) / b.v);
    }

    friend SMD_HD SMD_INLINE bool operator<(Dual a, Dual b) { return a.v < b.v; }
    friend SMD_HD SMD_INLINE bool operator>(Dual a, Dual b) { return a.v > b.v; }
    friend SMD_HD SMD_INLINE bool operator<=(Dual a, Dual b) { return a.v <= b.v; }
    friend SMD_HD SMD_INLINE bool operator>=(Dual a, Dual b) { return a.v >= b.v; }
    friend SMD_HD SMD_INLINE bool operator==(Dual a, Dual b) { return a.v == b.v; }
    friend SMD_HD SMD_INLINE bool operator!=(Dual a, Dual b) { return a.v != b.v; }

    friend SMD_HD SMD_INLINE Dual sqrt(Dual a) {
        const R s = sqrt(a.v);
        return Dual(s, a.d / (R(2) * s));
    }
    friend SMD_HD SMD_INLINE Dual cbrt(Dual a) {
        const R c = cbrt(a.v);
        return Dual(c, a.d / (R(3) * c * c));
    }
    friend SMD_HD SMD_INLINE Dual exp(Dual a) {
        const R e = exp(a.v);
        return Dual(e, a.d * e);
    }
    friend SMD_HD SMD_INLINE Dual log(Dual a) { return Dual(log(a.v), a.d / a.v); }
    friend SMD_HD SMD_INLINE Dual pow(Dual a, Dual b) {
        const R p = pow(a.v, b.v);
        // d(a^b) = b a^(b-1) da + a^b ln(a) db; the second part only where b varies.
        const R db = b.d == R(0) ? R(0) : p * log(a.v) * b.d;
        return Dual(p, b.v * pow(a.v, b.v - R(1)) * a.d + db);
    }
    friend SMD_HD SMD_INLINE Dual sin(Dual a) { return Dual(sin(a.v), a.d * cos(a.v)); }
    friend SMD_HD SMD_INLINE Dual cos(Dual a) { return Dual(cos(a.v), -a.d * sin(a.v)); }
    friend SMD_HD SMD_INLINE Dual tan(Dual a) {
        const R t = tan(a.v);
        return Dual(t, a.d * (R(1) + t * t));
    }
    friend SMD_HD SMD_INLINE Dual acos(Dual a) { return Dual(acos(a.v), -a.d / sqrt(R(1) - a.v * a.v)); }
    friend SMD_HD SMD_INLINE Dual asin(Dual a) { return Dual(asin(a.v), a.d / sqrt(R(1) - a.v * a.v)); }
    friend SMD_HD SMD_INLINE Dual atan(Dual a) { return Dual(atan(a.v), a.d / (R(1) + a.v * a.v)); }
    friend SMD_HD SMD_INLINE Dual atan2(Dual y, Dual x) {
        return Dual(atan2(y.v, x.v), (x.v * y.d - y.v * x.d) / (x.v * x.v + y.v * y.v));
    }
    friend SMD_HD SMD_INLINE Dual sinh(Dual a) { return Dual(sinh(a.v), a.d * cosh(a.v)); }
    friend SMD_HD SMD_INLINE Dual cosh(Dual a) { return Dual(cosh(a.v), a.d * sinh(a.v)); }
    friend SMD_HD SMD_INLINE Dual tanh(Dual a) {
        const R t = tanh(a.v);
        return Dual(t, a.d * (R(1) - t * t));
    }
    // d erf(x)/dx = 2/sqrt(pi) exp(-x^2)
    friend SMD_HD SMD_INLINE Dual erf(Dual a) {
        return Dual(erf(a.v), a.d * R(1.1283791670955126) * exp(-a.v * a.v));
    }
    friend SMD_HD SMD_INLINE Dual erfc(Dual a) {
        return Dual(erfc(a.v), -a.d * R(1.1283791670955126) * exp(-a.v * a.v));
    }
    friend SMD_HD SMD_INLINE Dual fabs(Dual a) { return a.v < R(0) ? -a : a; }
    friend SMD_HD SMD_INLINE Dual abs(Dual a) { return fabs(a); }
    friend SMD_HD SMD_INLINE Dual floor(Dual a) { return Dual(floor(a.v), R(0)); }
    friend SMD_HD SMD_INLINE Dual ceil(Dual a) { return Dual(ceil(a.v), R(0)); }
    friend SMD_HD SMD_INLINE Dual rint(Dual a) { return Dual(rint(a.v), R(0)); }
    friend SMD_HD SMD_INLINE Dual round(Dual a) { return Dual(round(a.v), R(0)); }
    friend SMD_HD SMD_INLINE Dual copysign(Dual a, Dual b) { return (a.v < R(0)) != (b.v < R(0)) ? -a : a; }
    friend SMD_HD SMD_INLINE Dual min(Dual a, Dual b) { return b.v < a.v ? b : a; }
    friend SMD_HD SMD_INLINE Dual max(Dual a, Dual b) { return a.v < b.v ? b : a; }
    friend SMD_HD SMD_INLINE Dual fmin(Dual a, Dual b) { return min(a, b); }
    friend SMD_HD SMD_INLINE Dual fmax(Dual a, Dual b) { return max(a, b); }
    friend SMD_HD SMD_INLINE bool isfinite(Dual a) { return isfinite(a.v) && isfinite(a.d); }
    friend SMD_HD SMD_INLINE bool isnan(Dual a) { return isnan(a.v) || isnan(a.d); }
};

template <>
SMD_HD SMD_INLINE constexpr Dual<float> machine_epsilon<Dual<float>>() {
    return Dual<float>(machine_epsilon<float>(), 0.0f);
}
template <>
SMD_HD SMD_INLINE constexpr Dual<double> machine_epsilon<Dual<double>>() {
    return Dual<double>(machine_epsilon<double>(), 0.0);
}
template <>
SMD_HD SMD_INLINE Dual<float> quiet_nan<Dual<float>>() {
    return Dual<float>(quiet_nan<float>(), quiet_nan<float>());
}
template <>
SMD_HD SMD_INLINE Dual<double> quiet_nan<Dual<double>>() {
    return Dual<double>(quiet_nan<double>(), quiet_nan<double>());
}

}  // namespace structmd

#if SMD_HOST_CODE
// What host code asks of a real type (an infinite cutoff of a bond, the largest value), for Dual.
namespace std {
template <class R>
class numeric_limits<structmd::Dual<R>> : public numeric_limits<R> {
public:
    static constexpr structmd::Dual<R> infinity() noexcept { return {std::numeric_limits<R>::infinity(), R(0)}; }
    static constexpr structmd::Dual<R> quiet_NaN() noexcept { return {std::numeric_limits<R>::quiet_NaN(), R(0)}; }
    static constexpr structmd::Dual<R> max() noexcept { return {std::numeric_limits<R>::max(), R(0)}; }
    static constexpr structmd::Dual<R> lowest() noexcept { return {std::numeric_limits<R>::lowest(), R(0)}; }
    static constexpr structmd::Dual<R> min() noexcept { return {std::numeric_limits<R>::min(), R(0)}; }
    static constexpr structmd::Dual<R> epsilon() noexcept { return {std::numeric_limits<R>::epsilon(), R(0)}; }
};
}  // namespace std
#endif
