#pragma once
// Clashed: a soft repulsion between overlapping particles of radii a_i, a_j:
//   U(r) = lambda (d^2 - r^2)^2   for r < d = gamma (a_i + a_j), else 0,
//   U'(r)/r = -4 lambda (d^2 - r^2).
// Every pair of the list interacts (no table); the range is 2 gamma times the largest radius, set by
// gamma and the radii rather than a cutOffFactor. U and U' reach 0 at d, so shift changes nothing.
#include "forcefield/pair_potential.hpp"

namespace structmd {

struct Clashed {
    static constexpr bool uses_radii = true;
    static constexpr const char* cutoff_key = "parameters.gamma";

    template <class R>
    struct Params {
        R lambda;
        R gamma;
        R cutoff2;  // (2 gamma a_max)^2, the longest d of any pair
    };

    static std::vector<Parameter> pair_parameters() { return {}; }
    static std::vector<Parameter> entry_parameters() {
        return {number("lambda", "energy/length^4", Must::be_non_negative), number("gamma", "1", Must::be_positive)};
    }

    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants& c, double, bool) {
        const double cutoff = 2.0 * v["gamma"] * c.largestRadius;
        return {R(v["lambda"]), R(v["gamma"]), R(cutoff * cutoff)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p, R radius_i, R radius_j) {
        const R d = p.gamma * (radius_i + radius_j);
        const R overlap = d * d - r2;
        if (!(overlap > R(0))) return {R(0), R(0)};
        return {R(-4) * p.lambda * overlap, p.lambda * overlap * overlap};
    }
};

}  // namespace structmd
