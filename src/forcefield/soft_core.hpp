#pragma once
// Soft-core potentials of lambda (lambda_coupling.hpp), as UAMMD-structured defines them: with
//   D = alpha (1 - lambda)^2 + (r/s)^6,
//   U(r, lambda) = lambda^n eps (c12 / D^2 + c6 / D)
// and (c12, c6) = (0, 1) Steric6SoftCore, (1, 0) Steric12SoftCore, (4, -4) LennardJonesSoftCoreType1,
// (1, -2) LennardJonesSoftCoreType2. At lambda = 1 they are eps (s/r)^6, eps (s/r)^12 and the
// Lennard-Jones shapes 1 and 2 (lennard_jones.hpp); below 1 the term alpha (1 - lambda)^2 keeps U
// finite at r = 0, so particles can be grown into a system without overlaps blowing up.
//   U'(r)/r     = lambda^n eps (-2 c12 / D^3 - c6 / D^2) 6 (r/s)^6 / r^2
//   dU/dlambda  = eps [n lambda^(n-1) (c12 / D^2 + c6 / D) + lambda^n (-2 c12 / D^3 - c6 / D^2) dD/dlambda],
//   dD/dlambda  = -2 alpha (1 - lambda).
// The NonBonded form is cut at cutOffFactor x sigma; shifted, U(r_c, lambda) is subtracted (a
// function of lambda, so dU/dlambda subtracts its derivative too). The Bond2 form has no cutoff.
#include <limits>

#include "forcefield/lambda_coupling.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {

template <int C12, int C6>
struct SoftCore {
    template <class R>
    struct Params {
        R epsilon;
        R sigma2;
        R alpha;
        R cutoff2;     // 0 for a type pair that does not interact, +infinity for a bond
        R cutoffRatio6;  // (r_c/s)^6 when shifted, else 0 (no shift)
        LambdaCoupling coupling;
    };

    static std::vector<Parameter> pair_parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)};
    }
    static std::vector<Parameter> entry_parameters() {
        return {number("alpha", "1", Must::be_non_negative), LambdaCoupling::power()};
    }
    template <class R>
    static Params<R> make_pair_params(const ParameterValues& v, const Constants& c, double cutOffFactor, bool shift) {
        const double cutoff = cutOffFactor * v["sigma"];
        if (!(cutoff > 0.0)) return {R(0), R(0), R(0), R(0), R(0), LambdaCoupling::from(v, c)};
        const double ratio2 = cutOffFactor * cutOffFactor;
        return {R(v["epsilon"]), R(v["sigma"] * v["sigma"]), R(v["alpha"]), R(cutoff * cutoff),
                R(shift ? ratio2 * ratio2 * ratio2 : 0.0), LambdaCoupling::from(v, c)};
    }

    // alpha and n are given once in the entry's "parameters" (registered as common).
    static std::vector<Parameter> bond_parameters() {
        std::vector<Parameter> schema = pair_parameters();
        for (const Parameter& p : entry_parameters()) schema.push_back(p);
        return schema;
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants& c) {
        return {R(v["epsilon"]), R(v["sigma"] * v["sigma"]), R(v["alpha"]), std::numeric_limits<R>::infinity(), R(0),
                LambdaCoupling::from(v, c)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        PairTerm<R> term{R(0), R(0)};
        if (!(r2 < p.cutoff2)) return term;
        const R lambda = p.coupling.template value<R>();
        R unusedDerivative;
        const R prefactor = p.epsilon * lambda_power(lambda, p.coupling.n, unusedDerivative);
        const R soft = p.alpha * (R(1) - lambda) * (R(1) - lambda);
        const R s2 = r2 / p.sigma2;
        const R s6 = s2 * s2 * s2;
        const R D = soft + s6;
        term.energy = prefactor * (shape(D) - shift_shape(soft, p));
        // dD/dr = 6 (r/s)^6 / r
        term.dudr_over_r = prefactor * shape_slope(D) * R(6) * s6 / r2;
        return term;
    }

    template <class R>
    static SMD_HD SMD_INLINE R lambda_derivative(R r2, const Params<R>& p) {
        if (!(r2 < p.cutoff2)) return R(0);
        const R lambda = p.coupling.template value<R>();
        R powerDerivative;
        const R power = lambda_power(lambda, p.coupling.n, powerDerivative);
        const R soft = p.alpha * (R(1) - lambda) * (R(1) - lambda);
        const R softDerivative = R(-2) * p.alpha * (R(1) - lambda);
        const R s2 = r2 / p.sigma2;
        const R D = soft + s2 * s2 * s2;
        R shapeValue = shape(D), slope = shape_slope(D);
        if (p.cutoffRatio6 > R(0)) {
            shapeValue -= shape(soft + p.cutoffRatio6);
            slope -= shape_slope(soft + p.cutoffRatio6);
        }
        return p.epsilon * (powerDerivative * shapeValue + power * slope * softDerivative);
    }

private:
    template <class R>
    static SMD_HD SMD_INLINE R shape(R D) {
        const R inverse = R(1) / D;
        return (R(C12) * inverse + R(C6)) * inverse;
    }
    // d shape / dD
    template <class R>
    static SMD_HD SMD_INLINE R shape_slope(R D) {
        const R inverse = R(1) / D;
        return -(R(2 * C12) * inverse + R(C6)) * inverse * inverse;
    }
    template <class R>
    static SMD_HD SMD_INLINE R shift_shape(R soft, const Params<R>& p) {
        return p.cutoffRatio6 > R(0) ? shape(soft + p.cutoffRatio6) : R(0);
    }
};

using Steric6SoftCore = SoftCore<0, 1>;
using Steric12SoftCore = SoftCore<1, 0>;
using LennardJonesSoftCoreType1 = SoftCore<4, -4>;
using LennardJonesSoftCoreType2 = SoftCore<1, -2>;

}  // namespace structmd
