#pragma once
// The real-space part of the Ewald sum of ["LongRange","Electrostatics"] (electrostatics.hpp), a
// pair term over the engine's neighbour list. Charges are Gaussians of width w (point charges for
// w = 0); the reciprocal part carries Gaussians of the wider width s, and this term the difference:
//   U(r) = k_e q_i q_j [erfc(r / 2s) - erfc(r / 2w)] / r,   k_e = f / eps_r,
// cut where it falls below the tolerance (the reciprocal part holds the rest of the interaction).
#include "core/hd.hpp"
#include "forcefield/pair_term.hpp"

namespace structmd {

struct EwaldNearField {
    static constexpr bool uses_charges = true;

    template <class R>
    struct Params {
        R prefactor;         // k_e = f / eps_r
        R inverse_far;       // 1 / 2s
        R inverse_gaussian;  // 1 / 2w; 0 for point charges (w = 0), whose second term vanishes
        R cutoff2;
    };

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p, R charge_product) {
        PairTerm<R> term{R(0), R(0)};
        if (!(r2 < p.cutoff2)) return term;
        const R two_over_sqrt_pi = R(1.1283791670955126);
        const R r = sqrt(r2);
        const R inv_r = R(1) / r;
        const R far = p.inverse_far * r;
        R screened = erfc(far);
        R slope = -two_over_sqrt_pi * p.inverse_far * exp(-far * far);  // d/dr of the numerator
        if (p.inverse_gaussian > R(0)) {
            const R own = p.inverse_gaussian * r;
            screened -= erfc(own);
            slope += two_over_sqrt_pi * p.inverse_gaussian * exp(-own * own);
        }
        const R k = p.prefactor * charge_product;
        term.energy = k * screened * inv_r;
        term.dudr_over_r = (k * slope * inv_r - term.energy * inv_r) * inv_r;
        return term;
    }
};

}  // namespace structmd
