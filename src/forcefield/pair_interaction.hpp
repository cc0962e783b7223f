#pragma once
// A non-bonded pair term over a Verlet list, generic in its potential. Each particle sums the
// forces of all its neighbours (a full list): no atomics, the same code on every backend, and a
// summation order fixed by the list. Energy and virial of a pair are split equally between the two.
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "forcefield/interactor.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

// Potentials of charges (Debye-Hueckel) declare `static constexpr bool uses_charges = true`.
template <class Potential, class = void>
struct UsesCharges : std::false_type {};
template <class Potential>
struct UsesCharges<Potential, std::void_t<decltype(Potential::uses_charges)>>
    : std::bool_constant<Potential::uses_charges> {};

template <class Potential, class R>
SMD_HD SMD_INLINE PairTerm<R> evaluate_pair(R r2, const typename Potential::template Params<R>& p, R chargeProduct) {
    if constexpr (UsesCharges<Potential>::value)
        return Potential::evaluate(r2, p, chargeProduct);
    else
        return Potential::evaluate(r2, p);
}

// Positions, separations and sums in R; the potential itself in PairR (float under mixed precision:
// the separation is taken in double, so its accuracy does not fall with the size of the box).
template <class Potential, class R, class PairR, bool WantForce, bool WantEnergy, bool WantVirial>
struct PairKernel {
    using Params = typename Potential::template Params<PairR>;
    const Real4<R>* pos;
    const R* charge;       // read only by potentials of charges
    const uint8_t* group;  // null: every particle takes part
    NeighbourView<R> neighbours;
    const Params* table;  // ntypes x ntypes
    int ntypes;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i, Lanes lanes) const {
        if (group && !group[i]) return;
        const Real4<R> pi = pos[i];
        const Vec3<R> ri = xyz(pi);
        const Params* row = table + static_cast<int>(pi.w) * ntypes;
        Vec3<R> f{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        const Box<R>& box = neighbours.box;
        neighbours.for_each_neighbour(static_cast<int>(i), ri, [&](int j) {
            const Real4<R> pj = pos[j];
            const Vec3<R> rij = box.minimum_image(xyz(pj) - ri);
            const PairR r2 = PairR(dot(rij, rij));
            const Params& p = row[static_cast<int>(pj.w)];
            if (!(r2 < p.cutoff2) || (group && !group[j])) return;
            const PairTerm<PairR> t = evaluate_pair<Potential>(
                r2, p, UsesCharges<Potential>::value ? PairR(charge[i] * charge[j]) : PairR(0));
            const R dudrOverR = R(t.dudr_over_r);
            if (WantForce) f += dudrOverR * rij;
            if (WantEnergy) e += R(0.5) * R(t.energy);
            if (WantVirial) w += (R(-0.5) * dudrOverR) * outer(rij, rij);
        }, lanes);
        if (WantForce) f = lanes.sum(f);
        if (WantEnergy) e = lanes.sum(e);
        if (WantVirial) w = lanes.sum(w);
        if (lanes.leader()) add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w);
    }
};

template <class B, class R, class Potential, class PairR = R>
class PairInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<PairR>;

    PairInteraction(const B& backend, InteractorScope scope, std::shared_ptr<VerletList<B, R>> list,
                    const std::vector<Params>& table, int ntypes)
        : Interactor<B, R>(std::move(scope)), backend_(backend), list_(std::move(list)), ntypes_(ntypes) {
        backend_.upload(table_, table.data(), table.size());
    }

    bool pairwise() const override { return true; }

    void prepare(Particles<B, R>& p) override { list_->update(p.pos, p.count, p.box, p.version); }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        const NeighbourView<R> view = list_->view();
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            backend_.for_each_lanes(particles.count,
                              PairKernel<Potential, R, PairR, decltype(force)::value, decltype(energy)::value,
                                         decltype(virial)::value>{particles.pos.data(), particles.charge.data(),
                                                                  this->group(), view, table_.data(), ntypes_,
                                                                  out});
        });
    }

private:
    const B& backend_;
    std::shared_ptr<VerletList<B, R>> list_;
    typename B::template Buffer<Params> table_;
    int ntypes_;
};

}  // namespace structmd
