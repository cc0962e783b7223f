#pragma once
// DLVO colloids: a Lennard-Jones term of the pair's type row plus the screened electrostatics of two
// charged spheres of radii a_i, a_j (their charge spread so that the field outside is Debye-Hueckel):
//   U(r) = eps shape(s/r)                                                  for r < r_np = cutOffNPFactor x s
//        + f q_i q_j exp(-(r - a_i - a_j)/l_D) / (eps_r r (1 + a_i/l_D)(1 + a_j/l_D))
//                                                                          for r < r_dh = cutOffDHFactor x l_D,
// with the shapes of lennard_jones.hpp. The electrostatics acts between every pair of the list,
// listed in the table or not (the table's rows only add the Lennard-Jones term). shift subtracts each
// term's value at its own cutoff.
#include <algorithm>
#include <cmath>

#include "forcefield/debye_huckel.hpp"
#include "forcefield/lennard_jones.hpp"

namespace structmd {

template <class Shape>
struct DLVO {
    static constexpr bool uses_charges = true;
    static constexpr bool uses_radii = true;
    static constexpr const char* cutoff_key = "parameters";

    template <class R>
    struct Params {
        LennardJonesParams<R> lennard_jones;  // zero cutoff: no Lennard-Jones term (unlisted type pair)
        R prefactor;                          // f / eps_r
        R inverse_length;                     // 1 / l_D
        R electrostatic_cutoff2;
        R shifted_at;  // r_dh when shifted, else 0
        R cutoff2;     // the larger of the two
    };

    static std::vector<Parameter> pair_parameters() { return EpsilonSigmaPair<DLVO>::pair_parameters(); }
    static std::vector<Parameter> entry_parameters() { return contact_and_screening_parameters(); }

    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants& c, double, bool shift) {
        Params<R> p = make_unlisted_pair_params<R>(v, c, 0.0, shift);
        p.lennard_jones =
            make_cut_lennard_jones<Shape, R>(v["epsilon"], v["sigma"], v["cutOffNPFactor"] * v["sigma"], 0.0, shift);
        p.cutoff2 = std::max(p.cutoff2, p.lennard_jones.cutoff2);
        return p;
    }

    template <class R>
    static Params<R> make_unlisted_pair_params(const ParameterValues& v, const Constants& c, double, bool shift) {
        const double debyeLength = v["debyeLength"];
        const double cutoff = v["cutOffDHFactor"] * debyeLength;
        return {LennardJonesParams<R>{},
                R(c.electricConversion / v["dielectricConstant"]),
                R(1.0 / debyeLength),
                R(cutoff * cutoff),
                R(shift ? cutoff : 0.0),
                R(cutoff * cutoff)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p, R charge_product, R radius_i,
                                                  R radius_j) {
        PairTerm<R> term = evaluate_lennard_jones<Shape>(r2, p.lennard_jones);
        if (!(r2 < p.electrostatic_cutoff2) || charge_product == R(0)) return term;
        const R r = sqrt(r2);
        const R contact = radius_i + radius_j;
        const R strength = p.prefactor * charge_product /
                           ((R(1) + radius_i * p.inverse_length) * (R(1) + radius_j * p.inverse_length));
        const R u = strength * exp(-(r - contact) * p.inverse_length) / r;
        // U'(r) = -U (1/l_D + 1/r)
        term.dudr_over_r += -u * (p.inverse_length + R(1) / r) / r;
        term.energy += u;
        if (p.shifted_at > R(0))
            term.energy -= strength * exp(-(p.shifted_at - contact) * p.inverse_length) / p.shifted_at;
        return term;
    }
};

using DLVOType1 = DLVO<LennardJonesShape1>;
using DLVOType2 = DLVO<LennardJonesShape2>;
using DLVOType3 = DLVO<LennardJonesShape3>;

}  // namespace structmd
