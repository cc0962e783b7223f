#pragma once
// Shared by the bonded-functor tests: random chains in a small periodic box (half of them straddling
// its boundary, the functor getting positions chained by minimum image from wrapped ones, as the
// engine gives them), angles computed independently of the functors, and the checks every functor
// goes through: forces against central finite differences of its own energy, zero net force and
// torque, and the float instantiation against the double one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "core/box.hpp"
#include "core/vec.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {
namespace bonded_test {

using V = Vec3<double>;

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr int kSamples = 200;
inline constexpr double kFiniteDifferenceStep = 1e-6;
inline constexpr double kForceTolerance = 1e-6;   // relative, forces against finite differences
inline constexpr double kFloatTolerance = 1e-4;   // relative, float against double
inline constexpr double kBalanceTolerance = 1e-12;  // relative, net force and torque

inline const Box<double> kBox = Box<double>::make(2.6, 3.0, 3.4);
inline const Constants kConstants{};

inline double& component(V& v, int axis) { return axis == 0 ? v.x : (axis == 1 ? v.y : v.z); }
inline double component_of(V v, int axis) { return component(v, axis); }
inline double length(V v) { return std::sqrt(dot(v, v)); }
inline double max_abs(V v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }
inline V cross_product(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V unit(V v) { return (1.0 / length(v)) * v; }

inline V random_direction(std::mt19937_64& rng) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    return unit(V{gauss(rng), gauss(rng), gauss(rng)});
}

// N particles bonded in a chain: their unwrapped positions, and the positions the functor receives
// (the first particle's wrapped position, then each next one by the minimum image of the difference
// of wrapped positions).
template <int N>
struct Chain {
    V unwrapped[N];
    V r[N];
    bool straddles = false;  // some bond crosses the periodic boundary
};

template <int N>
Chain<N> chain_from(const V* unwrapped) {
    Chain<N> chain;
    V wrapped[N];
    for (int k = 0; k < N; ++k) {
        chain.unwrapped[k] = unwrapped[k];
        wrapped[k] = kBox.wrap(unwrapped[k]);
    }
    chain.r[0] = wrapped[0];
    for (int k = 1; k < N; ++k) {
        chain.r[k] = chain.r[k - 1] + kBox.minimum_image(wrapped[k] - wrapped[k - 1]);
        if (max_abs((wrapped[k] - wrapped[k - 1]) - (unwrapped[k] - unwrapped[k - 1])) > 1e-9) chain.straddles = true;
    }
    return chain;
}

// Sample `sample`: bonds of length 0.6..1.2 (below half the box) in random directions; odd samples
// start within 0.4 of a box face so that the chain usually crosses it.
template <int N>
Chain<N> random_chain(std::mt19937_64& rng, int sample) {
    std::uniform_real_distribution<double> unit_interval(0.0, 1.0);
    V x[N];
    x[0] = {(unit_interval(rng) - 0.5) * kBox.length.x, (unit_interval(rng) - 0.5) * kBox.length.y,
            (unit_interval(rng) - 0.5) * kBox.length.z};
    if (sample % 2 == 1) {
        const int axis = static_cast<int>(unit_interval(rng) * 3.0) % 3;
        const double half = 0.5 * component_of(kBox.length, axis);
        component(x[0], axis) = (unit_interval(rng) < 0.5 ? 1.0 : -1.0) * (half - 0.4 * unit_interval(rng));
    }
    for (int k = 1; k < N; ++k) x[k] = x[k - 1] + (0.6 + 0.6 * unit_interval(rng)) * random_direction(rng);
    return chain_from<N>(x);
}

// The angle at b of a-b-c, from the arc cosine of the normalised dot product.
inline double angle_by_arc_cosine(V a, V b, V c) {
    const V u = a - b, w = c - b;
    return std::acos(std::clamp(dot(u, w) / (length(u) * length(w)), -1.0, 1.0));
}

// The IUPAC dihedral of a-b-c-d from the angle between the two outer bonds projected on the plane
// normal to the axis b -> c, signed positive when the bond to a turns clockwise (seen looking from b
// towards c) to eclipse the bond to d, that is when (b->a projected) x (c->d projected) points along
// the axis.
inline double dihedral_by_projection(V a, V b, V c, V d) {
    const V axis = unit(c - b);
    V front = a - b;
    V back = d - c;
    front = front - dot(front, axis) * axis;
    back = back - dot(back, axis) * axis;
    const double magnitude = std::acos(std::clamp(dot(front, back) / (length(front) * length(back)), -1.0, 1.0));
    return dot(cross_product(front, back), axis) >= 0.0 ? magnitude : -magnitude;
}

template <class Term>
using ParamsOf = typename Term::template Params<double>;

// max |F - F_fd| / max(max |F_fd|, floor), F_fd = -(U(r + h e) - U(r - h e)) / 2h per coordinate.
template <class Term>
inline double finite_difference_error(const V* r, const ParamsOf<Term>& p, double floor, double h = kFiniteDifferenceStep) {
    constexpr int N = Term::arity;
    V force[N];
    Term::compute(r, p, kBox, force);
    double worst_difference = 0.0, largest = 0.0;
    for (int k = 0; k < N; ++k)
        for (int axis = 0; axis < 3; ++axis) {
            V shifted[N], scratch[N];
            std::copy(r, r + N, shifted);
            component(shifted[k], axis) += h;
            const double up = Term::compute(shifted, p, kBox, scratch);
            component(shifted[k], axis) -= 2.0 * h;
            const double down = Term::compute(shifted, p, kBox, scratch);
            const double expected = -(up - down) / (2.0 * h);
            worst_difference = std::max(worst_difference, std::fabs(component(force[k], axis) - expected));
            largest = std::max(largest, std::fabs(expected));
        }
    return worst_difference / std::max(largest, floor);
}

struct Balance {
    double net_force;  // |sum F| / max |F|
    double torque;     // |sum r x F| / (max |F| max |r|)
};

template <int N>
inline Balance balance_of(const V* r, const V* force) {
    V net{0, 0, 0}, torque{0, 0, 0};
    double largest_force = 0.0, largest_position = 0.0;
    for (int k = 0; k < N; ++k) {
        net += force[k];
        torque += cross_product(r[k], force[k]);
        largest_force = std::max(largest_force, length(force[k]));
        largest_position = std::max(largest_position, length(r[k]));
    }
    return {length(net) / largest_force, length(torque) / (largest_force * largest_position)};
}

// Energy and force of the float instantiation against the double one, relative to
// max(|U|, energy_scale) and max(max |F|, force_scale): the scales keep the comparison relative to
// the term's strength where U or F happens to be near zero. `constants`: the units and temperature
// the parameters are made with.
struct FloatAgreement {
    double energy;
    double force;
};

template <class Term>
inline FloatAgreement float_agreement(const V* r, const double* values, double energy_scale, double force_scale,
                                      const Constants& constants = kConstants) {
    constexpr int N = Term::arity;
    const auto pd = Term::template make_params<double>(values_in_order(Term::parameters(), values), constants);
    const auto pf = Term::template make_params<float>(values_in_order(Term::parameters(), values), constants);
    const Box<float> box_f = Box<float>::make(kBox.length.x, kBox.length.y, kBox.length.z);
    Vec3<float> rf[N], ff[N];
    V fd[N];
    for (int k = 0; k < N; ++k) rf[k] = {float(r[k].x), float(r[k].y), float(r[k].z)};
    const double ed = Term::compute(r, pd, kBox, fd);
    const double ef = Term::compute(rf, pf, box_f, ff);
    double worst = 0.0, largest = 0.0;
    for (int k = 0; k < N; ++k) {
        const V f_as_double{ff[k].x, ff[k].y, ff[k].z};
        worst = std::max(worst, max_abs(f_as_double - fd[k]));
        largest = std::max(largest, max_abs(fd[k]));
    }
    return {std::fabs(ef - ed) / std::max(std::fabs(ed), energy_scale), worst / std::max(largest, force_scale)};
}

inline void report(const char* what, double worst) { std::printf("[ worst    ] %s: %.3g\n", what, worst); }

// Random three-particle chains with theta at least 0.1 rad away from 0 and pi.
inline std::vector<Chain<3>> angle_chains(unsigned seed) {
    std::mt19937_64 rng(seed);
    std::vector<Chain<3>> chains;
    int straddling = 0;
    for (int sample = 0; static_cast<int>(chains.size()) < kSamples; ++sample) {
        const Chain<3> c = random_chain<3>(rng, sample);
        const double theta = angle_by_arc_cosine(c.unwrapped[0], c.unwrapped[1], c.unwrapped[2]);
        if (theta < 0.1 || theta > kPi - 0.1) continue;
        straddling += c.straddles;
        chains.push_back(c);
    }
    EXPECT_GT(straddling, kSamples / 5) << "too few geometries cross the boundary to test it";
    return chains;
}

// Random four-particle chains whose two bond angles are at least 0.15 rad away from 0 and pi.
inline std::vector<Chain<4>> dihedral_chains(unsigned seed) {
    std::mt19937_64 rng(seed);
    std::vector<Chain<4>> chains;
    int straddling = 0;
    for (int sample = 0; static_cast<int>(chains.size()) < kSamples; ++sample) {
        const Chain<4> c = random_chain<4>(rng, sample);
        const double first = angle_by_arc_cosine(c.unwrapped[0], c.unwrapped[1], c.unwrapped[2]);
        const double second = angle_by_arc_cosine(c.unwrapped[1], c.unwrapped[2], c.unwrapped[3]);
        if (std::min(first, second) < 0.15 || std::max(first, second) > kPi - 0.15) continue;
        straddling += c.straddles;
        chains.push_back(c);
    }
    EXPECT_GT(straddling, kSamples / 5) << "too few geometries cross the boundary to test it";
    return chains;
}

}  // namespace bonded_test
}  // namespace structmd
