#pragma once
// Anisotropic harmonic springs: one spring per Cartesian axis, on the size of that component of a
// separation d,
//   U(d) = sum_a 1/2 K_a (|d_a| - r0_a)^2,   a = x, y, z,   r0_a >= 0,
// with d = minimum_image(r_j - r_i) between two particles (["Bond2","HarmonicAnisotropic"]) or
// d = minimum_image(p - r_i) from a particle to a fixed point p (["Bond1","FixedHarmonicAnisotropic"]).
// U depends on |d_a| only, as UAMMD-structured computes it: mirroring d through any axis (swapping
// the two particles included) leaves it unchanged, and its minima are at d_a = +-r0_a.
// dU/dd_a = K_a (|d_a| - r0_a) sign(d_a). At d_a = 0 with r0_a > 0 the spring of axis a has a cusp (a
// maximum, left with slopes -+K_a r0_a on either side) and no gradient: its force is taken as zero
// there, the mean of the two one-sided values, so that the term stays symmetric in the particles
// (UAMMD-structured takes sign(0) = -1, a force of K_a r0_a along one of the two directions, which
// depends on the order of the particles). With r0_a = 0 zero is the exact, smooth gradient.
#include "forcefield/bond_potential.hpp"

namespace structmd {
namespace anisotropic_spring {

template <class R>
struct Params {
    Vec3<R> K;
    Vec3<R> r0;
};

inline std::vector<Parameter> parameters() {
    return {numbers("K", 3, "energy/length^2"), numbers("r0", 3, "length", Must::be_non_negative)};
}

// The spring of one axis: its energy, and dU/dd_a in `slope`.
template <class R>
SMD_HD SMD_INLINE R axis(R d, R K, R r0, R& slope) {
    const R sign = d > R(0) ? R(1) : (d < R(0) ? R(-1) : R(0));
    const R stretch = sign * d - r0;  // |d| - r0
    slope = K * stretch * sign;
    return R(0.5) * K * stretch * stretch;
}

// U(d), and its gradient dU/dd in `gradient`.
template <class R>
SMD_HD SMD_INLINE R energy(Vec3<R> d, const Params<R>& p, Vec3<R>& gradient) {
    return axis(d.x, p.K.x, p.r0.x, gradient.x) + axis(d.y, p.K.y, p.r0.y, gradient.y) +
           axis(d.z, p.K.z, p.r0.z, gradient.z);
}

template <class R>
Params<R> make_params(const ParameterValues& v) {
    const std::array<double, 3> K = v.vec3("K");
    const std::array<double, 3> r0 = v.vec3("r0");
    return {{R(K[0]), R(K[1]), R(K[2])}, {R(r0[0]), R(r0[1]), R(r0[2])}};
}

}  // namespace anisotropic_spring

// ["Bond2","HarmonicAnisotropic"]: d = r[1] - r[0] (the functor's positions are already minimum
// images of each other); F_j = -dU/dd, F_i = +dU/dd.
struct HarmonicAnisotropicBond {
    static constexpr int arity = 2;
    static constexpr bool under_domains = true;  // reader_entries.hpp: runs_under_domains

    template <class R>
    using Params = anisotropic_spring::Params<R>;

    static std::vector<Parameter> parameters() { return anisotropic_spring::parameters(); }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return anisotropic_spring::make_params<R>(v);
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        Vec3<R> gradient;
        const R energy = anisotropic_spring::energy(r[1] - r[0], p, gradient);
        force[0] = gradient;
        force[1] = -gradient;
        return energy;
    }
};

// ["Bond1","FixedHarmonicAnisotropic"]: d = minimum_image(point - r[0]); the point may lie outside
// the box. F_i = -dU/dr_i = +dU/dd.
struct FixedHarmonicAnisotropic {
    static constexpr int arity = 1;

    template <class R>
    struct Params {
        anisotropic_spring::Params<R> spring;
        Vec3<R> point;
    };

    static std::vector<Parameter> parameters() {
        std::vector<Parameter> schema = anisotropic_spring::parameters();
        schema.push_back(numbers("position", 3, "length"));
        return schema;
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        const std::array<double, 3> point = v.vec3("position");
        return {anisotropic_spring::make_params<R>(v), {R(point[0]), R(point[1]), R(point[2])}};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>& box, Vec3<R>* force) {
        Vec3<R> gradient;
        const R energy = anisotropic_spring::energy(box.wrap(p.point - r[0]), p.spring, gradient);
        force[0] = gradient;
        return energy;
    }
};

}  // namespace structmd
