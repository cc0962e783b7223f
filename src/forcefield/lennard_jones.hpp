#pragma once
// The Lennard-Jones family. Every member is U(r) = eps shape(s/r) + offset inside its cutoff and 0
// beyond, with one of three shapes, each of minimum -1:
//   type 1: 4 [(s/r)^12 - (s/r)^6]     minimum at r = 2^(1/6) s
//   type 2: (s/r)^12 - 2 (s/r)^6       minimum at r = s
//   type 3: 5 (s/r)^12 - 6 (s/r)^10    minimum at r = s
// (and Karanicolas-Brooks's 13 (s/r)^12 - 18 (s/r)^10 + 4 (s/r)^6, minimum -1 at r = s, a Bond2 only).
// This file holds the shapes, the shared Params and evaluation, and LennardJonesTypeK: the NonBonded
// form cut at r_c (the energy jumps there unless shifted, which subtracts U(r_c)) and the Bond2 form,
// which has no cutoff. The WCA and general forms are in lennard_jones_wca.hpp and
// lennard_jones_general.hpp.
#include <limits>

#include "core/real_limits.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {

// A shape's value and r d(shape)/dr, from (s/r)^2.
template <class R>
struct LennardJonesShapeTerm {
    R radial_derivative;
    R value;
};

struct LennardJonesShape1 {
    static double minimum_distance(double sigma) { return std::pow(2.0, 1.0 / 6.0) * sigma; }

    template <class R>
    static SMD_HD SMD_INLINE LennardJonesShapeTerm<R> at(R sr2) {
        const R sr6 = sr2 * sr2 * sr2;
        const R sr12 = sr6 * sr6;
        return {R(24) * (sr6 - R(2) * sr12), R(4) * (sr12 - sr6)};
    }
};

struct LennardJonesShape2 {
    static double minimum_distance(double sigma) { return sigma; }

    template <class R>
    static SMD_HD SMD_INLINE LennardJonesShapeTerm<R> at(R sr2) {
        const R sr6 = sr2 * sr2 * sr2;
        const R sr12 = sr6 * sr6;
        return {R(12) * (sr6 - sr12), sr12 - R(2) * sr6};
    }
};

struct LennardJonesShape3 {
    static double minimum_distance(double sigma) { return sigma; }

    template <class R>
    static SMD_HD SMD_INLINE LennardJonesShapeTerm<R> at(R sr2) {
        const R sr4 = sr2 * sr2;
        const R sr10 = sr4 * sr4 * sr2;
        const R sr12 = sr10 * sr2;
        return {R(60) * (sr10 - sr12), R(5) * sr12 - R(6) * sr10};
    }
};

// Karanicolas and Brooks's native-contact form (a Bond2 of Go-like models): 13 (s/r)^12 - 18 (s/r)^10
// + 4 (s/r)^6, minimum -1 at r = s with a small barrier beyond it.
struct LennardJonesShapeKaranicolasBrooks {
    static double minimum_distance(double sigma) { return sigma; }
    template <class R>
    static SMD_HD SMD_INLINE LennardJonesShapeTerm<R> at(R sr2) {
        const R sr4 = sr2 * sr2;
        const R sr6 = sr4 * sr2;
        const R sr10 = sr6 * sr4;
        const R sr12 = sr6 * sr6;
        return {R(180) * sr10 - R(156) * sr12 - R(24) * sr6, R(13) * sr12 - R(18) * sr10 + R(4) * sr6};
    }
};

template <class R>
struct LennardJonesParams {
    R epsilon;
    R sigma2;
    R cutoff2;  // 0 for a type pair that does not interact, +infinity for a bond
    R offset;   // added inside the cutoff: +eps for WCA, minus the value at r_c when shifted
};

template <class Shape, class R>
SMD_HD SMD_INLINE PairTerm<R> evaluate_lennard_jones(R r2, const LennardJonesParams<R>& p) {
    PairTerm<R> term{R(0), R(0)};
    if (!(r2 < p.cutoff2)) return term;
    const R inv_r2 = reciprocal(r2);
    const LennardJonesShapeTerm<R> s = Shape::at(p.sigma2 * inv_r2);
    term.dudr_over_r = p.epsilon * s.radial_derivative * inv_r2;
    term.energy = p.epsilon * s.value + p.offset;
    return term;
}

// U = eps shape + constant for r < cutoff; shifted, the value at the cutoff is subtracted so that U
// reaches 0 there. A cutoff that is not positive gives a pair that does not interact.
template <class Shape, class R>
LennardJonesParams<R> make_cut_lennard_jones(double epsilon, double sigma, double cutoff, double constant,
                                             bool shifted) {
    if (!(cutoff > 0.0)) return {R(0), R(0), R(0), R(0)};
    const double sigma2 = sigma * sigma;
    const double cutoff2 = cutoff * cutoff;
    const double offset = shifted ? -epsilon * Shape::template at<double>(sigma2 / cutoff2).value : constant;
    return {R(epsilon), R(sigma2), R(cutoff2), R(offset)};
}

template <class Shape>
struct LennardJones : EpsilonSigmaPair<LennardJones<Shape>> {
    static constexpr bool under_domains = true;  // reader_entries.hpp: runs_under_domains
    template <class R>
    using Params = LennardJonesParams<R>;
    using EpsilonSigmaPair<LennardJones<Shape>>::make_pair_params;

    template <class R>
    static Params<R> make_pair_params(double epsilon, double sigma, double cutoff, bool shifted) {
        return make_cut_lennard_jones<Shape, R>(epsilon, sigma, cutoff, 0.0, shifted);
    }

    static std::vector<Parameter> bond_parameters() { return LennardJones::pair_parameters(); }

    // A bond has no cutoff.
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants&) {
        return {R(v["epsilon"]), R(v["sigma"] * v["sigma"]), std::numeric_limits<R>::infinity(), R(0)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        return evaluate_lennard_jones<Shape>(r2, p);
    }
};

using LennardJonesType1 = LennardJones<LennardJonesShape1>;
using LennardJonesType2 = LennardJones<LennardJonesShape2>;
using LennardJonesType3 = LennardJones<LennardJonesShape3>;
using LennardJonesKaranicolasBrooks = LennardJones<LennardJonesShapeKaranicolasBrooks>;

}  // namespace structmd
