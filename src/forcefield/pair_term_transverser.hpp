#pragma once
// A pair potential as a transverser (transverser/transverser.hpp), the special case UAMMD's PairForces
// module runs: a pair's Compute is its force on i, half its energy and half its virial, summed as
// PairKernel (pair_kernel.hpp) sums them over a list. Over a neighbour list it gives what PairKernel
// gives; over all pairs (AllPairsTraversal) it is a pair potential without a list, whose only reach
// is the table's cutoff: the building block of pair terms of no finite range.
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/force_outputs.hpp"
#include "forcefield/pair_kernel.hpp"
#include "transverser/transverser.hpp"

namespace structmd {

template <class Potential, class R, class PairR, bool WantForce, bool WantEnergy, bool WantVirial>
struct PairTermTransverser {
    using Params = typename Potential::template Params<PairR>;
    using Info = int;  // the particle's index: charges and radii are read by the potentials that use them
    struct Compute {
        Vec3<R> force;
        R energy;
        Tensor3<R> virial;
    };

    const R* charge;  // by particle, read only by potentials of charges
    const R* radius;  // by particle, read only by potentials of radii
    PairTable<Params> table;
    ForceOutputs<R> out;

    SMD_HD SMD_INLINE Compute zero() const { return {{R(0), R(0), R(0)}, R(0), zero_tensor<R>()}; }
    SMD_HD SMD_INLINE int info(int i) const { return i; }

    SMD_HD SMD_INLINE Compute compute(const Real4<R>& ri, const Real4<R>& rj, int i, int j) const {
        const Vec3<R> rij = xyz(rj) - xyz(ri);
        const PairR r2 = PairR(dot(rij, rij));
        const Params& p = table.row_of(i, static_cast<int>(ri.w))[static_cast<int>(rj.w)];
        Compute c = zero();
        if (!(r2 < p.cutoff2)) return c;
        const PairTerm<PairR> t = evaluate_pair_of<Potential>(r2, p, charge, radius, i, j);
        const R dudrOverR = R(t.dudr_over_r);
        if (WantForce) c.force = dudrOverR * rij;
        if (WantEnergy) c.energy = R(0.5) * R(t.energy);
        if (WantVirial) c.virial = (R(-0.5) * dudrOverR) * outer(rij, rij);
        return c;
    }

    SMD_HD SMD_INLINE void accumulate(Compute& total, const Compute& c) const {
        if (WantForce) total.force += c.force;
        if (WantEnergy) total.energy += c.energy;
        if (WantVirial) total.virial += c.virial;
    }

    SMD_HD SMD_INLINE void set(int i, const Compute& total) const {
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, total.force, total.energy, total.virial);
    }
};

}  // namespace structmd
