#pragma once
// UAMMD-structured's ["NonBonded","StericInner6"] and ["NonBonded","StericInner12"]: steric repulsion
// between every pair of the list whose size is the sum of the particles' inner radii (the state's
// innerRadius column) rather than a parameter of their types:
//   U(r) = eps (sigma_ij / r)^n   for r < cutOffFactor sigma_ij, else 0,   sigma_ij = a_i + a_j,
// n = 6 or 12; shift subtracts U at the cutoff, eps cutOffFactor^-n. The list's range is cutOffFactor
// times the sum of the two largest inner radii, as UAMMD-structured takes it. The inner radii are read
// by steric_inner_read.cpp into the entry's config and given to the pair kernels in place of the
// particles' radii.
#include <cmath>
#include <memory>
#include <vector>

#include "core/real_limits.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/interactor_tables.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from the entry: each particle's inner radius and the sum of the two largest.
struct InnerRadiiConfig : ComponentConfig {
    std::vector<double> innerRadius;
    double largestSigma = 0.0;
};

template <int Exponent>
struct StericInnerPotential {
    static_assert(Exponent > 0 && Exponent % 2 == 0, "the power is taken of (s/r)^2");
    static constexpr bool uses_radii = true;

    template <class R>
    struct Params {
        R epsilon;
        R cutOffFactor2;
        R cutoff2;  // the list's range, the longest pair cutoff
        R shift;    // U at each pair's cutoff when shifted, else 0
    };

    static std::vector<Parameter> entry_parameters() { return {number("epsilon", "energy")}; }

    template <class R>
    static Params<R> make_params(const ParameterValues& v, double cutOffFactor, bool shift, double cutoff) {
        const double epsilon = v["epsilon"];
        return {R(epsilon), R(cutOffFactor * cutOffFactor), R(cutoff * cutoff),
                R(shift ? epsilon * std::pow(cutOffFactor, -Exponent) : 0.0)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p, R innerRadiusI, R innerRadiusJ) {
        const R sigma = innerRadiusI + innerRadiusJ;
        const R sigma2 = sigma * sigma;
        if (!(r2 < p.cutOffFactor2 * sigma2)) return {R(0), R(0)};
        const R inv_r2 = reciprocal(r2);
        const R sr2 = sigma2 * inv_r2;
        R srn = sr2;
        for (int k = 1; k < Exponent / 2; ++k) srn *= sr2;
        const R u = p.epsilon * srn;
        return {R(-Exponent) * u * inv_r2, u - p.shift};  // U'(r)/r = -n U / r^2
    }
};

template <int Exponent>
struct StericInnerComponent {
    using Potential = StericInnerPotential<Exponent>;
    static ForceFieldComponent reader_entry(ComponentKey key);  // steric_inner_read.cpp

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& pair = static_cast<const PairSpec&>(s);
        const auto& config = static_cast<const InnerRadiiConfig&>(*s.config);
        const auto tableIn = [&](auto real) {
            using T = decltype(real);
            return pair_table_of<typename Potential::template Params<T>>(
                pair, build.context, [&](const ParameterValues& v) {
                    return Potential::template make_params<T>(v, pair.cutOffFactor, pair.shift,
                                                              pair.cutOffFactor * config.largestSigma);
                });
        };
        auto radii = std::make_shared<typename B::template Buffer<R>>();
        const std::vector<R> host(config.innerRadius.begin(), config.innerRadius.end());
        build.backend.upload(*radii, host.data(), host.size());
        auto interactor = std::make_unique<PairInteraction<B, R, Potential, PairR>>(
            build.backend, build.scope(pair), build.listFor(pair), tableIn(PairR{}),
            static_cast<int>(build.context.ntypes), nullptr, radii->data());
        interactor->own(radii);
        if (build.context.hessian) interactor->enable_hessian(tableIn(Dual<PairR>{}));
        return interactor;
    }
};

}  // namespace structmd
