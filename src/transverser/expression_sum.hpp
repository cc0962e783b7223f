#pragma once
// The expression transverser: each particle's sum over its pairs of an expression of the pair,
// f(r, dx, dy, dz, type_i, type_j, charge_i, charge_j, radius_i, radius_j, mass_i, mass_j), such as
// "r < 1.5" (the coordination number) or "exp(-r^2)" (a smoothed local density). Generic in how the
// expression is evaluated, as the Expression potentials are (forcefield/expression_terms.hpp): a
// Function with Params<R> and evaluate(inputs, params, outputs), outputs[0] being the value; the
// interpreter on the CPU backend, the expression compiled at load on CUDA. Free of the standard
// library, so that kernels compiled at run time include it.
#include "core/hd.hpp"
#include "core/vec.hpp"

namespace structmd {

// The expression's inputs, in the order of their slots.
enum ExpressionSumInput : int {
    kSumR,
    kSumDx,  // the separation r_j - r_i, by minimum image
    kSumDy,
    kSumDz,
    kSumTypeI,
    kSumTypeJ,
    kSumChargeI,
    kSumChargeJ,
    kSumRadiusI,
    kSumRadiusJ,
    kSumMassI,
    kSumMassJ,
    kSumInputs
};

template <class Function, class R>
struct ExpressionSum {
    struct Info {
        R charge, radius, mass;
    };
    using Compute = R;

    typename Function::template Params<R> function;
    const R* charge;             // by particle; null: 0
    const R* radius;             // by particle; null: 0
    const Real4<R>* velocities;  // by particle, w: the mass; null: 0
    R* out;                      // by particle

    SMD_HD SMD_INLINE R zero() const { return R(0); }
    SMD_HD SMD_INLINE Info info(int i) const {
        return {charge ? charge[i] : R(0), radius ? radius[i] : R(0), velocities ? velocities[i].w : R(0)};
    }
    SMD_HD SMD_INLINE R compute(const Real4<R>& ri, const Real4<R>& rj, const Info& a, const Info& b) const {
        const Vec3<R> d = xyz(rj) - xyz(ri);
        // R(...): without the standard library's overloads (clang's host pass, NVRTC) sqrt of a
        // float may be the double one.
        const R r = R(sqrt(dot(d, d)));
        const R inputs[kSumInputs] = {r, d.x, d.y, d.z, ri.w, rj.w, a.charge, b.charge, a.radius, b.radius, a.mass, b.mass};
        R value[1];
        Function::evaluate(inputs, function, value);
        return value[0];
    }
    SMD_HD SMD_INLINE void accumulate(R& total, const R& current) const { total += current; }
    SMD_HD SMD_INLINE void set(int i, const R& total) const { out[i] = total; }
};

}  // namespace structmd
