#pragma once
// Newtonian gravity between point masses, optionally softened (Plummer):
//   U(r) = -G m_i m_j / sqrt(r^2 + eps^2)
// at every distance, G the gravitational constant (in the input's units) and eps the softening length
// (0: none). It has no cutoff, so it runs over all pairs (an ["NBody", "all"] list) of a box open along
// every axis. The masses are the particles' own (the state's, else their type's). structmd's own
// (UAMMD-structured has no gravity).
#include <limits>
#include <vector>

#include "forcefield/pair_potential.hpp"

namespace structmd {

struct Gravity {
    static constexpr bool uses_masses = true;  // all_pairs_interaction.hpp: the masses' products
    static constexpr bool infinite_range = true;

    template <class R>
    struct Params {
        R prefactor;   // -G
        R softening2;  // eps^2
        R cutoff2;     // infinity: every pair interacts
    };

    static std::vector<Parameter> pair_parameters() { return {}; }
    static std::vector<Parameter> entry_parameters() {
        return {number("G", "energy length/mass^2", Must::be_non_negative),
                with_default(number("softening", "length", Must::be_non_negative), 0.0)};
    }
    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants&, double, bool) {
        return {R(-v["G"]), R(v["softening"] * v["softening"]), std::numeric_limits<R>::infinity()};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p, R mass_product) {
        const R inv_s = R(1) / sqrt(r2 + p.softening2);
        const R u = p.prefactor * mass_product * inv_s;
        // U'(r)/r = -U / (r^2 + eps^2)
        return {-u * inv_s * inv_s, u};
    }
};

}  // namespace structmd
