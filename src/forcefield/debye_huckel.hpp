#pragma once
// Debye-Hueckel screened electrostatics: U(r) = f q_i q_j exp(-r/l_D) / (eps_r r) for r < r_c, else 0,
// with f the electric conversion factor of the units, eps_r the relative dielectric constant and l_D
// the Debye length. The NonBonded form takes the charges per pair (evaluate(r2, p, q_i q_j)); shift
// subtracts U(r_c). The Bond2 form folds its given charge product into the prefactor (evaluate(r2, p)).
#include "forcefield/pair_potential.hpp"

namespace structmd {

// The parameters of a contact term with screened electrostatics (DLVO, KimHummer), given once in the
// entry: each part's range (in units of sigma and of the Debye length) and the medium.
inline std::vector<Parameter> contact_and_screening_parameters() {
    return {number("cutOffNPFactor", "1", Must::be_positive), number("cutOffDHFactor", "1", Must::be_positive),
            number("dielectricConstant", "1", Must::be_positive), number("debyeLength", "length", Must::be_positive)};
}

struct DebyeHuckel {
    static constexpr bool uses_charges = true;  // a domain's ghosts carry their charges
    static constexpr bool under_domains = true;  // reader_entries.hpp: runs_under_domains

    template <class R>
    struct Params {
        R prefactor;       // f / eps_r, times the charge product for a bond
        R inverse_length;  // 1 / l_D
        R cutoff2;         // 0: does not interact
        R shift;           // prefactor exp(-r_c/l_D) / r_c when shifted, else 0
    };

    // NonBonded: the same for every type pair (the charges make the difference), cut at
    // cutOffFactor x debyeLength.
    static std::vector<Parameter> pair_parameters() { return {}; }
    static std::vector<Parameter> entry_parameters() {
        return {number("dielectricConstant", "1", Must::be_positive), number("debyeLength", "length", Must::be_positive)};
    }
    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants& c, double cutOffFactor, bool shift) {
        return make_params<R>(v["dielectricConstant"], v["debyeLength"], cutOffFactor * v["debyeLength"], c, shift);
    }

    template <class R>
    static Params<R> make_params(double dielectricConstant, double debyeLength, double cutoff, const Constants& c,
                                 bool shifted = false) {
        return make<R>(c.electricConversion / dielectricConstant, debyeLength, cutoff, shifted);
    }

    static std::vector<Parameter> bond_parameters() {
        return {number("chgProduct", "charge^2"), number("dielectricConstant", "1", Must::be_positive),
                number("debyeLength", "length", Must::be_positive), number("cutOff", "length", Must::be_positive)};
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants& c) {
        return make<R>(c.electricConversion * v["chgProduct"] / v["dielectricConstant"], v["debyeLength"], v["cutOff"],
                       false);
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        PairTerm<R> term{R(0), R(0)};
        if (!(r2 < p.cutoff2)) return term;
        const R r = sqrt(r2);
        const R inv_r = R(1) / r;
        const R u = p.prefactor * exp(-r * p.inverse_length) * inv_r;
        // U'(r) = -U (1/l_D + 1/r)
        term.dudr_over_r = -u * (p.inverse_length + inv_r) * inv_r;
        term.energy = u - p.shift;
        return term;
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p, R charge_product) {
        const PairTerm<R> unit = evaluate(r2, p);
        return {charge_product * unit.dudr_over_r, charge_product * unit.energy};
    }

private:
    template <class R>
    static Params<R> make(double prefactor, double debyeLength, double cutoff, bool shifted) {
        if (!(cutoff > 0.0)) return {R(0), R(0), R(0), R(0)};
        const double shift = shifted ? prefactor * std::exp(-cutoff / debyeLength) / cutoff : 0.0;
        return {R(prefactor), R(1.0 / debyeLength), R(cutoff * cutoff), R(shift)};
    }
};

}  // namespace structmd
