#pragma once
// Kim-Hummer residue-level protein model (Kim & Hummer, J. Mol. Biol. 375, 1416 (2008)): a non-polar
// contact term of the pair's type row plus Debye-Hueckel electrostatics (debye_huckel.hpp). With
// g(r) = 4 [(s/r)^12 - (s/r)^6] and r_0 = 2^(1/6) s, the contact term of a row (eps, s) is
//   eps < 0:  |eps| g(r)                                   (attractive Lennard-Jones, depth |eps|)
//   eps > 0:  eps g(r) + 2 eps for r < r_0, -eps g(r) beyond  (repulsive, +eps at r_0, continuous)
//   eps = 0:  zeroEnergy (s/r)^12                          (excluded volume only)
// for r < r_np = cutOffNPFactor x s, and the electrostatics f q_i q_j exp(-r/l_D) / (eps_r r) for
// r < r_dh = cutOffDHFactor x l_D acts between every pair of the list, listed in the table or not.
// shift subtracts each term's value at its own cutoff. Only SASA model A (every weight 1, the
// default) is computed: models B-F weigh each particle by its solvent accessible surface area, which
// no input can give (UAMMD-structured has no state label for it and stops without it); naming one
// is refused.
#include <algorithm>
#include <cmath>

#include "core/real_limits.hpp"
#include "forcefield/debye_huckel.hpp"
#include "forcefield/lennard_jones.hpp"

namespace structmd {

struct KimHummer {
    static constexpr bool uses_charges = true;
    static constexpr const char* cutoff_key = "parameters";

    template <class R>
    struct Params {
        R epsilon;      // the row's, with its sign: it picks the form
        R zero_energy;  // the strength of the eps = 0 form
        R sigma2;
        R contact2;        // r_0^2, where the repulsive form turns
        R contact_cutoff2; // r_np^2; 0: no contact term (unlisted type pair)
        R contact_offset;  // -(contact term at r_np) when shifted, else 0
        DebyeHuckel::Params<R> electrostatics;
        R cutoff2;  // the larger of the two
    };

    static std::vector<Parameter> pair_parameters() { return EpsilonSigmaPair<KimHummer>::pair_parameters(); }
    static std::vector<TextOption> text_options() {
        return {{"sasaModel", "A", {"A"}, {"B", "C", "D", "E", "F"},
                 "SASA models B-F weigh each particle by its solvent accessible surface area, which structmd's "
                 "state does not hold; \"A\" (no weighting) is computed"}};
    }
    static std::vector<Parameter> entry_parameters() {
        std::vector<Parameter> parameters = contact_and_screening_parameters();
        parameters.push_back(with_default(number("zeroEnergy", "energy", Must::be_non_negative), 0.01));
        return parameters;
    }

    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants& c, double, bool shift) {
        const double sigma = v["sigma"];
        const double cutoff = v["cutOffNPFactor"] * sigma;
        const Params<double> unshifted{v["epsilon"], v["zeroEnergy"], sigma * sigma, std::cbrt(2.0) * sigma * sigma,
                                       cutoff * cutoff, 0.0, DebyeHuckel::Params<double>{}, 0.0};
        Params<R> p = make_unlisted_pair_params<R>(v, c, 0.0, shift);
        p.epsilon = R(unshifted.epsilon);
        p.zero_energy = R(unshifted.zero_energy);
        p.sigma2 = R(unshifted.sigma2);
        p.contact2 = R(unshifted.contact2);
        p.contact_cutoff2 = R(unshifted.contact_cutoff2);
        p.contact_offset = R(shift ? -contact(unshifted.contact_cutoff2, unshifted).energy : 0.0);
        p.cutoff2 = std::max(p.cutoff2, p.contact_cutoff2);
        return p;
    }

    template <class R>
    static Params<R> make_unlisted_pair_params(const ParameterValues& v, const Constants& c, double, bool shift) {
        Params<R> p{};
        p.electrostatics = DebyeHuckel::make_params<R>(v["dielectricConstant"], v["debyeLength"],
                                                       v["cutOffDHFactor"] * v["debyeLength"], c, shift);
        p.cutoff2 = p.electrostatics.cutoff2;
        return p;
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p, R charge_product) {
        PairTerm<R> term = DebyeHuckel::evaluate(r2, p.electrostatics, charge_product);
        if (r2 < p.contact_cutoff2) {
            const PairTerm<R> c = contact(r2, p);
            term.dudr_over_r += c.dudr_over_r;
            term.energy += c.energy + p.contact_offset;
        }
        return term;
    }

private:
    // The contact term without its cutoff.
    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> contact(R r2, const Params<R>& p) {
        const R inv_r2 = reciprocal(r2);
        const R sr2 = p.sigma2 * inv_r2;
        if (p.epsilon == R(0)) {
            const R sr6 = sr2 * sr2 * sr2;
            const R u = p.zero_energy * sr6 * sr6;
            return {R(-12) * u * inv_r2, u};
        }
        const LennardJonesShapeTerm<R> g = LennardJonesShape1::at(sr2);
        if (p.epsilon < R(0)) return {-p.epsilon * g.radial_derivative * inv_r2, -p.epsilon * g.value};
        if (r2 < p.contact2) return {p.epsilon * g.radial_derivative * inv_r2, p.epsilon * (g.value + R(2))};
        return {-p.epsilon * g.radial_derivative * inv_r2, -p.epsilon * g.value};
    }
};

}  // namespace structmd
