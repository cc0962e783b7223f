#pragma once
// Terms coupled to the ensemble's lambda (["Ensemble","NVTlambda"]), for alchemical transformations
// and thermodynamic integration. Such a term's Params hold a LambdaCoupling: where lambda lives on
// the backend (read at every evaluation, so a simulation step may change it between steps without
// rebuilding anything) and the power n of its prefactor lambda^n. Besides its usual evaluation it
// has dU/dlambda:
//   pair potential:  template <class R> static SMD_HD R lambda_derivative(R r2, const Params<R>& p);
//   bonded term:     template <class R> static SMD_HD R lambda_derivative(const Vec3<R>* r,
//                                                                         const Params<R>& p, const Box<R>& box);
// The wrappers below present dU/dlambda as the "energy" of a potential with no force, so that the
// ordinary pair and bond kernels sum it per particle (split as energies are) into any buffer.
#include <type_traits>

#include "core/box.hpp"
#include "core/hd.hpp"
#include "core/parameters.hpp"
#include "core/vec.hpp"
#include "forcefield/bond_potential.hpp"
#include "forcefield/pair_potential.hpp"
#include "forcefield/pair_term.hpp"

namespace structmd {

struct LambdaCoupling {
    const double* lambda;  // one value on the backend
    int n;                 // the prefactor is lambda^n, n >= 1

    static Parameter power() { return with_default(number("n", "1", Must::be_positive_integer), 2.0); }
    static LambdaCoupling from(const ParameterValues& v, const Constants& c) {
        return {c.lambda, static_cast<int>(v["n"])};
    }

    template <class R>
    SMD_HD SMD_INLINE R value() const {
        return R(*lambda);
    }
};

// lambda^n, and its derivative n lambda^(n-1) in `derivative`, by repeated products (n >= 1).
template <class R>
SMD_HD SMD_INLINE R lambda_power(R lambda, int n, R& derivative) {
    R below = R(1);  // lambda^(k-1)
    for (int k = 1; k < n; ++k) below *= lambda;
    derivative = R(n) * below;
    return below * lambda;
}

template <class Potential, class = void>
struct couples_to_lambda : std::false_type {};
template <class Potential>
struct couples_to_lambda<Potential, std::void_t<decltype(&Potential::template lambda_derivative<double>)>>
    : std::true_type {};

// A pair potential's dU/dlambda as the energy of a forceless pair potential with the same Params.
template <class Potential>
struct PairLambdaDerivative {
    template <class R>
    using Params = typename Potential::template Params<R>;

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        return {R(0), Potential::lambda_derivative(r2, p)};
    }
};

// A radial pair potential of lambda as a two-particle bond (bond_potential.hpp's RadialBond), with
// its dU/dlambda.
template <class Radial>
struct RadialLambdaBond : RadialBond<Radial> {
    template <class R>
    static SMD_HD SMD_INLINE R lambda_derivative(const Vec3<R>* r, const typename Radial::template Params<R>& p,
                                                 const Box<R>&) {
        const Vec3<R> d = r[1] - r[0];
        return Radial::lambda_derivative(dot(d, d), p);
    }
};

// A bonded term's dU/dlambda as the energy of a forceless bonded term with the same Params.
template <class Potential>
struct BondLambdaDerivative {
    static constexpr int arity = Potential::arity;
    template <class R>
    using Params = typename Potential::template Params<R>;

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>& box, Vec3<R>* force) {
        for (int k = 0; k < arity; ++k) force[k] = Vec3<R>{R(0), R(0), R(0)};
        return Potential::lambda_derivative(r, p, box);
    }
};

}  // namespace structmd
