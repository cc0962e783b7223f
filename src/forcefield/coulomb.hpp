#pragma once
// Unscreened electrostatics between point charges: U(r) = f q_i q_j / (eps_r r) at every distance, with
// f the electric conversion factor of the units and eps_r the relative dielectric constant. It has no
// cutoff, so it runs over all pairs (an ["NBody", "all"] list) of a box open along every axis, where
// the sum over pairs is the whole energy (a periodic box needs Ewald: ["LongRange","Electrostatics"]).
// structmd's own (UAMMD-structured has no unscreened pair term).
#include <limits>
#include <vector>

#include "forcefield/pair_potential.hpp"

namespace structmd {

struct Coulomb {
    static constexpr bool uses_charges = true;
    static constexpr bool infinite_range = true;  // component_registry.hpp: runs over all pairs only

    template <class R>
    struct Params {
        R prefactor;  // f / eps_r
        R cutoff2;    // infinity: every pair interacts
    };

    static std::vector<Parameter> pair_parameters() { return {}; }
    static std::vector<Parameter> entry_parameters() {
        return {number("dielectricConstant", "1", Must::be_positive)};
    }
    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants& c, double, bool) {
        return {R(c.electricConversion / v["dielectricConstant"]), std::numeric_limits<R>::infinity()};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p, R charge_product) {
        const R inv_r = R(1) / sqrt(r2);
        const R u = p.prefactor * charge_product * inv_r;
        // U'(r)/r = -U / r^2
        return {-u * inv_r * inv_r, u};
    }
};

}  // namespace structmd
