// A structmd plugin: a transverser giving each particle's local density, a Gaussian-weighted sum of
// the masses of the particles around it,
//
//   rho_i = sum_{j != i} m_j exp(-r_ij^2 / (2 sigma^2))
//
// sigma (length) its one parameter: structmd_traverse(sim, "LocalDensity", "{\"sigma\": 0.8}", ...).
// The traversal decides which j: those closer than the cutoff, or every one for cutoff 0. Written once
// for every backend against the Transverser contract (transverser/transverser.hpp).
#include "engines/plugin.hpp"

namespace {

using namespace structmd;

struct LocalDensity {
    static constexpr int values = 1;
    static std::vector<Parameter> parameters() { return {number("sigma", "length", Must::be_positive)}; }

    template <class R>
    struct Functor {
        using Info = R;  // the particle's mass
        using Compute = R;
        const Real4<R>* velocities;  // w: the mass; null: every mass 1
        R minusHalfOverSigma2;
        R* out;

        SMD_HD R zero() const { return R(0); }
        SMD_HD R info(int i) const { return velocities ? velocities[i].w : R(1); }
        SMD_HD R compute(const Real4<R>& ri, const Real4<R>& rj, R, R massJ) const {
            const Vec3<R> d = xyz(rj) - xyz(ri);
            return massJ * exp(minusHalfOverSigma2 * dot(d, d));
        }
        SMD_HD void accumulate(R& total, const R& current) const { total += current; }
        SMD_HD void set(int i, const R& total) const { out[i] = total; }
    };

    template <class R>
    static Functor<R> make(const TransverserInputs<R>& in, const ParameterValues& v) {
        const double sigma = v["sigma"];
        return {in.velocities, R(-0.5 / (sigma * sigma)), in.out};
    }
};

}  // namespace

STRUCTMD_PLUGIN(registrar) { registrar.transverser<LocalDensity>("LocalDensity"); }
