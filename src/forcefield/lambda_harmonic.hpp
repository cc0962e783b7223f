#pragma once
// Harmonic springs switched on by the ensemble's lambda (lambda_coupling.hpp): the spring's energy
// times lambda^n, n given once in the entry (default 2).
//   ["Bond2","LambdaHarmonic"]:                 U = lambda^n 1/2 K (r - r0)^2
//   ["Bond1","LambdaFixedHarmonicAnisotropic"]: U = lambda^n sum_a 1/2 K_a (|d_a| - r0_a)^2, d the
//       minimum image of position - r_i (harmonic_anisotropic.hpp, whose cusp rule it keeps)
// dU/dlambda = n lambda^(n-1) times the spring's energy.
#include "forcefield/harmonic_anisotropic.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "forcefield/lambda_coupling.hpp"

namespace structmd {

struct LambdaHarmonicBond {
    template <class R>
    struct Params {
        HarmonicBond::Params<R> spring;
        LambdaCoupling coupling;
    };

    // n is given once in the entry's "parameters" (registered as common).
    static std::vector<Parameter> bond_parameters() {
        std::vector<Parameter> schema = HarmonicBond::bond_parameters();
        schema.push_back(LambdaCoupling::power());
        return schema;
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants& c) {
        return {HarmonicBond::make_bond_params<R>(v, c), LambdaCoupling::from(v, c)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        R unusedDerivative;
        const R power = lambda_power(p.coupling.template value<R>(), p.coupling.n, unusedDerivative);
        const PairTerm<R> spring = HarmonicBond::evaluate(r2, p.spring);
        return {power * spring.dudr_over_r, power * spring.energy};
    }

    template <class R>
    static SMD_HD SMD_INLINE R lambda_derivative(R r2, const Params<R>& p) {
        R powerDerivative;
        lambda_power(p.coupling.template value<R>(), p.coupling.n, powerDerivative);
        return powerDerivative * HarmonicBond::evaluate(r2, p.spring).energy;
    }
};

struct LambdaFixedHarmonicAnisotropic {
    static constexpr int arity = 1;

    template <class R>
    struct Params {
        FixedHarmonicAnisotropic::Params<R> tether;
        LambdaCoupling coupling;
    };

    static std::vector<Parameter> parameters() {
        std::vector<Parameter> schema = FixedHarmonicAnisotropic::parameters();
        schema.push_back(LambdaCoupling::power());
        return schema;
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants& c) {
        return {FixedHarmonicAnisotropic::make_params<R>(v, c), LambdaCoupling::from(v, c)};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>& box, Vec3<R>* force) {
        R unusedDerivative;
        const R power = lambda_power(p.coupling.template value<R>(), p.coupling.n, unusedDerivative);
        const R energy = FixedHarmonicAnisotropic::compute(r, p.tether, box, force);
        force[0] = power * force[0];
        return power * energy;
    }

    template <class R>
    static SMD_HD SMD_INLINE R lambda_derivative(const Vec3<R>* r, const Params<R>& p, const Box<R>& box) {
        R powerDerivative;
        lambda_power(p.coupling.template value<R>(), p.coupling.n, powerDerivative);
        Vec3<R> unusedForce[1];
        return powerDerivative * FixedHarmonicAnisotropic::compute(r, p.tether, box, unusedForce);
    }
};

}  // namespace structmd
