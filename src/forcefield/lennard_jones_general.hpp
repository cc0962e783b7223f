#pragma once
// General Lennard-Jones: the sign of each pair's epsilon picks the form.
//   eps >= 0: the WCA form with eps (purely repulsive, lennard_jones_wca.hpp);
//   eps < 0:  the Lennard-Jones form with |eps|, cut at r_c (attractive well, lennard_jones.hpp).
// Either way shift subtracts the form's U(r_c).
#include <cmath>

#include "forcefield/lennard_jones_wca.hpp"

namespace structmd {

template <class Shape>
struct GeneralLennardJones : EpsilonSigmaPair<GeneralLennardJones<Shape>> {
    static constexpr bool under_domains = true;  // reader_entries.hpp: runs_under_domains
    template <class R>
    using Params = LennardJonesParams<R>;
    using EpsilonSigmaPair<GeneralLennardJones<Shape>>::make_pair_params;

    template <class R>
    static Params<R> make_pair_params(double epsilon, double sigma, double cutoff, bool shifted) {
        if (epsilon >= 0.0)
            return WeeksChandlerAndersen<Shape>::template make_pair_params<R>(epsilon, sigma, cutoff, shifted);
        return LennardJones<Shape>::template make_pair_params<R>(std::fabs(epsilon), sigma, cutoff, shifted);
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        return evaluate_lennard_jones<Shape>(r2, p);
    }
};

using GeneralLennardJonesType1 = GeneralLennardJones<LennardJonesShape1>;
using GeneralLennardJonesType2 = GeneralLennardJones<LennardJonesShape2>;
using GeneralLennardJonesType3 = GeneralLennardJones<LennardJonesShape3>;

}  // namespace structmd
