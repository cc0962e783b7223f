#pragma once
// Bond2 terms of a WCA core (the type-2 Lennard-Jones repulsion, eps [(s/r)^12 - 2 (s/r)^6] + eps for
// r < s, else 0) plus an attractive well whose minimum sits where the core ends:
//   MorseWCA:             U = E [(1 - exp(-(r - r0)/D))^2 - 1] + WCA2(eps0, s = r0)
//   LennardJonesGaussian: U = WCA2(eps, s) - eps exp(-(r - s)^2 / (2D))
// Both have U(r0 or s) = -well depth, continuous value and slope at the core's edge.
#include "forcefield/gaussian_bond.hpp"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/morse.hpp"

namespace structmd {

// The WCA core of epsilon and sigma^2.
template <class R>
SMD_HD SMD_INLINE PairTerm<R> wca_core(R r2, R epsilon, R sigma2) {
    return evaluate_lennard_jones<LennardJonesShape2>(r2, LennardJonesParams<R>{epsilon, sigma2, sigma2, epsilon});
}

template <class R>
SMD_HD SMD_INLINE PairTerm<R> sum_of(const PairTerm<R>& a, const PairTerm<R>& b) {
    return {a.dudr_over_r + b.dudr_over_r, a.energy + b.energy};
}

struct MorseWCABond {
    template <class R>
    struct Params {
        MorseBond::Params<R> morse;
        R coreEpsilon;
        R r02;
    };
    static std::vector<Parameter> bond_parameters() {
        std::vector<Parameter> parameters = MorseBond::bond_parameters();
        parameters.push_back(number("eps0", "energy"));
        return parameters;
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants& c) {
        return {MorseBond::make_bond_params<R>(v, c), R(v["eps0"]), R(v["r0"] * v["r0"])};
    }
    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        return sum_of(MorseBond::evaluate(r2, p.morse), wca_core(r2, p.coreEpsilon, p.r02));
    }
};

struct LennardJonesGaussianBond {
    template <class R>
    struct Params {
        GaussianBond::Params<R> well;  // depth epsilon at r0 = sigma
        R sigma2;
    };
    static std::vector<Parameter> bond_parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive),
                number("D", "length^2", Must::be_positive)};
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants&) {
        return {{R(v["epsilon"]), R(v["sigma"]), R(1.0 / v["D"])}, R(v["sigma"] * v["sigma"])};
    }
    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        return sum_of(wca_core(r2, p.well.depth, p.sigma2), GaussianBond::evaluate(r2, p.well));
    }
};

}  // namespace structmd
