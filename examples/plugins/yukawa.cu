// A structmd plugin: the Yukawa pair potential, which structmd does not ship, as ["NonBonded", "Yukawa"].
//
//   U(r) = epsilon (sigma / r) exp(-kappa (r - sigma))   for r < cutOffFactor x sigma, else 0
//
// epsilon (energy) and sigma (length) per type pair, kappa (1/length) once for the entry; "shift"
// subtracts U at the cutoff. The functor is written once for every backend (host and device), against
// the same contract as the built-in pair potentials (forcefield/pair_potential.hpp). Built as a .cu
// file, it also runs on the CUDA backend when structmd was built with CUDA.
#include "engines/plugin.hpp"

namespace {

using namespace structmd;

struct Yukawa {
    template <class R>
    struct Params {
        R epsilon, sigma, kappa;
        R cutoff2;  // 0: the type pair does not interact
        R shift;    // U(r_c) when shifted, else 0
    };

    static std::vector<Parameter> pair_parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)};
    }
    static std::vector<Parameter> entry_parameters() { return {number("kappa", "1/length", Must::be_non_negative)}; }

    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants&, double cutOffFactor, bool shift) {
        const double epsilon = v["epsilon"], sigma = v["sigma"], kappa = v["kappa"], cutoff = cutOffFactor * sigma;
        const double atCutoff = epsilon * sigma / cutoff * std::exp(-kappa * (cutoff - sigma));
        return {R(epsilon), R(sigma), R(kappa), R(cutoff * cutoff), R(shift ? atCutoff : 0.0)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        if (!(r2 < p.cutoff2)) return {R(0), R(0)};
        const R r = sqrt(r2);
        const R u = p.epsilon * p.sigma / r * exp(-p.kappa * (r - p.sigma));
        // U'(r) = -U (1/r + kappa)
        return {-u * (R(1) / r + p.kappa) / r, u - p.shift};
    }
};

}  // namespace

STRUCTMD_PLUGIN(registrar) { registrar.pair<Yukawa>({"NonBonded", "Yukawa"}); }
