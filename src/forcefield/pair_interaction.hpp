#pragma once
// A non-bonded pair term over a Verlet list, generic in its potential. Each particle sums the
// forces of all its neighbours (a full list): no atomics, the same code on every backend, and a
// summation order fixed by the list. Energy and virial of a pair are split equally between the two.
#include <memory>
#include <string>
#include <vector>

#include "forcefield/interactor.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

template <class Potential, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct PairKernel {
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    NeighbourView<R> neighbours;
    const Params* table;  // ntypes x ntypes
    int ntypes;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
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
            const R r2 = dot(rij, rij);
            const Params& p = row[static_cast<int>(pj.w)];
            if (!(r2 < p.cutoff2)) return;
            const PairTerm<R> t = Potential::evaluate(r2, p);
            if (WantForce) f += t.dudr_over_r * rij;
            if (WantEnergy) e += R(0.5) * t.energy;
            if (WantVirial) w += (R(-0.5) * t.dudr_over_r) * outer(rij, rij);
        });
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w);
    }
};

template <class B, class R, class Potential>
class PairInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<R>;

    PairInteraction(const B& backend, std::string name, std::shared_ptr<VerletList<B, R>> list,
                    const std::vector<Params>& table, int ntypes)
        : Interactor<B, R>(std::move(name)), backend_(backend), list_(std::move(list)), ntypes_(ntypes) {
        backend_.upload(table_, table.data(), table.size());
    }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        if (!list_) return;  // no type pair interacts
        const NeighbourView<R> view = list_->view();
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            backend_.for_each(particles.count,
                              PairKernel<Potential, R, decltype(force)::value, decltype(energy)::value,
                                         decltype(virial)::value>{particles.pos.data(), view, table_.data(),
                                                                  ntypes_, out});
        });
    }

private:
    const B& backend_;
    std::shared_ptr<VerletList<B, R>> list_;
    typename B::template Buffer<Params> table_;
    int ntypes_;
};

}  // namespace structmd
