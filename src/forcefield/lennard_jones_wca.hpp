#pragma once
// Weeks-Chandler-Andersen forms of the Lennard-Jones shapes (lennard_jones.hpp):
//   U(r) = eps shape(s/r) + eps for r < r_min, else 0,
// with r_min the shape's minimum (2^(1/6) s for type 1, s for types 2 and 3), where U reaches 0 with a
// zero derivative. The +eps also holds for type 1 (the reference adds eps/4 there and jumps at r_min).
// As a NonBonded entry the cutoff that acts is min(cutOffFactor x sigma, r_min): a cutOffFactor beyond
// r_min adds nothing, one short of it cuts the repulsion earlier, where shift subtracts U(r_c).
#include <algorithm>

#include "forcefield/lennard_jones.hpp"

namespace structmd {

template <class Shape>
struct WeeksChandlerAndersen : EpsilonSigmaPair<WeeksChandlerAndersen<Shape>> {
    static constexpr bool under_domains = true;  // reader_entries.hpp: runs_under_domains
    template <class R>
    using Params = LennardJonesParams<R>;
    using EpsilonSigmaPair<WeeksChandlerAndersen<Shape>>::make_pair_params;

    template <class R>
    static Params<R> make_pair_params(double epsilon, double sigma, double cutoff, bool shifted) {
        const double acting_cutoff = std::min(cutoff, Shape::minimum_distance(sigma));
        return make_cut_lennard_jones<Shape, R>(epsilon, sigma, acting_cutoff, epsilon, shifted);
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        return evaluate_lennard_jones<Shape>(r2, p);
    }
};

using WCAType1 = WeeksChandlerAndersen<LennardJonesShape1>;
using WCAType2 = WeeksChandlerAndersen<LennardJonesShape2>;
using WCAType3 = WeeksChandlerAndersen<LennardJonesShape3>;

}  // namespace structmd
