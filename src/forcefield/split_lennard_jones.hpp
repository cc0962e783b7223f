#pragma once
// Split Lennard-Jones: the type-1 shape g(r) = 4 [(s/r)^12 - (s/r)^6] (lennard_jones.hpp) with one
// energy scale for the repulsive core and another for the attractive well:
//   U(r) = eps_r g(r) + eps_r - eps_a   for r < r_min = 2^(1/6) s
//   U(r) = eps_a g(r)                   for r_min <= r < r_c = cutOffFactor x s, else 0,
// eps_r the entry's epsilon_r, eps_a the entry's epsilon_a times the row's epsilon (as the reference
// computes it; its docs leave the row's epsilon out). Both branches are -eps_a with zero slope at
// r_min, so energy and force are continuous there. shift subtracts U(r_c).
#include <cmath>

#include "core/real_limits.hpp"
#include "forcefield/lennard_jones.hpp"

namespace structmd {

struct SplitLennardJones {
    static constexpr bool under_domains = true;  // reader_entries.hpp: runs_under_domains
    template <class R>
    struct Params {
        R repulsive_epsilon;   // eps_r
        R attractive_epsilon;  // eps_a
        R sigma2;
        R minimum2;  // r_min^2, where the scales meet
        R cutoff2;   // 0 for a type pair that does not interact
        R offset;    // -U(r_c) when shifted, else 0
    };

    static std::vector<Parameter> pair_parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)};
    }
    static std::vector<Parameter> entry_parameters() { return {number("epsilon_r", "energy"), number("epsilon_a", "1")}; }

    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants&, double cutOffFactor, bool shift) {
        const double sigma = v["sigma"];
        const double cutoff = cutOffFactor * sigma;
        if (!(cutoff > 0.0)) return Params<R>{};
        const Params<double> p{v["epsilon_r"], v["epsilon_a"] * v["epsilon"], sigma * sigma,
                               std::cbrt(2.0) * sigma * sigma, cutoff * cutoff, 0.0};
        const double offset = shift ? -uncut(p.cutoff2, p).energy : 0.0;
        return {R(p.repulsive_epsilon), R(p.attractive_epsilon), R(p.sigma2), R(p.minimum2), R(p.cutoff2), R(offset)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        if (!(r2 < p.cutoff2)) return {R(0), R(0)};
        PairTerm<R> term = uncut(r2, p);
        term.energy += p.offset;
        return term;
    }

private:
    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> uncut(R r2, const Params<R>& p) {
        const R inv_r2 = reciprocal(r2);
        const LennardJonesShapeTerm<R> g = LennardJonesShape1::at(p.sigma2 * inv_r2);
        const bool core = r2 < p.minimum2;
        const R epsilon = core ? p.repulsive_epsilon : p.attractive_epsilon;
        const R constant = core ? p.repulsive_epsilon - p.attractive_epsilon : R(0);
        return {epsilon * g.radial_derivative * inv_r2, epsilon * g.value + constant};
    }
};

}  // namespace structmd
