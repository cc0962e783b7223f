#pragma once
// LaTorre: a flat attractive well out to r_min = 2^(1/6) s that fades to 0 over a width w (the tail
// attraction of the Cooke-Kremer-Deserno membrane model, used beside a WCA repulsion):
//   U(r) = -eps                                  for r <= r_min
//   U(r) = -eps cos^2(pi (r - r_min) / (2 w))    for r_min < r < r_min + w, else 0.
// The range r_min + w is each row's own; the entry reads no cutOffFactor. U and U' reach 0 at the end
// of the range, so shift changes nothing.
#include <cmath>

#include "forcefield/pair_potential.hpp"

namespace structmd {

struct LaTorre {
    static constexpr const char* cutoff_key = "data";

    template <class R>
    struct Params {
        R epsilon;
        R minimum;           // r_min, where the fading starts
        R phase_per_length;  // pi / (2 w)
        R cutoff2;           // (r_min + w)^2; 0 for a type pair that does not interact
    };

    static std::vector<Parameter> pair_parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive),
                number("w", "length", Must::be_positive)};
    }
    static std::vector<Parameter> entry_parameters() { return {}; }

    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants&, double, bool) {
        const double minimum = std::pow(2.0, 1.0 / 6.0) * v["sigma"];
        const double cutoff = minimum + v["w"];
        return {R(v["epsilon"]), R(minimum), R(M_PI / (2.0 * v["w"])), R(cutoff * cutoff)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        if (!(r2 < p.cutoff2)) return {R(0), R(0)};
        const R r = sqrt(r2);
        if (!(r > p.minimum)) return {R(0), -p.epsilon};
        const R phase = p.phase_per_length * (r - p.minimum);
        const R c = cos(phase);
        const R s = sin(phase);
        // U'(r) = 2 eps cos sin pi/(2w)
        const R dudr = R(2) * p.epsilon * c * s * p.phase_per_length;
        return {dudr / r, -p.epsilon * c * c};
    }
};

}  // namespace structmd
