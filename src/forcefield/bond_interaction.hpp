#pragma once
// Bonded terms of N = 1..4 particles, generic in their potential (bond_potential.hpp). Each particle
// visits the bonds it takes part in (a per-particle index built once at load) and keeps its own
// share: no atomics, and the same sum order on every backend. Energy and virial of a bond are split
// equally among its N particles; the virial of a bond is sum_k d_k (x) F_k with d_k the position of
// particle k relative to the first.
#include <cstdint>
#include <string>
#include <vector>

#include "forcefield/bond_potential.hpp"
#include "forcefield/interactor.hpp"

namespace structmd {

template <class Potential, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct BondKernel {
    static constexpr int N = Potential::arity;
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    Box<R> box;
    const int* firstEntry;  // entries of particle i: entries[firstEntry[i] .. firstEntry[i+1])
    const int* entries;     // bond * N + the particle's slot in that bond
    const int* members;     // particles of bond b: members[N b .. N b + N)
    const Params* params;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        Vec3<R> f{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        for (int k = firstEntry[i]; k < firstEntry[i + 1]; ++k) {
            const int b = entries[k] / N;
            const int slot = entries[k] % N;
            const int* ids = members + N * b;
            Vec3<R> r[N];
            r[0] = xyz(pos[ids[0]]);
            for (int m = 1; m < N; ++m)
                r[m] = r[m - 1] + box.minimum_image(xyz(pos[ids[m]]) - xyz(pos[ids[m - 1]]));
            Vec3<R> force[N];
            const R energy = Potential::compute(r, params[b], box, force);
            if (WantForce) f += force[slot];
            if (WantEnergy) e += energy / R(N);
            if (WantVirial)
                for (int m = 1; m < N; ++m) w += (R(1) / R(N)) * outer(r[m] - r[0], force[m]);
        }
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w);
    }
};

template <class B, class R, class Potential>
class BondInteraction : public Interactor<B, R> {
public:
    static constexpr int N = Potential::arity;
    using Params = typename Potential::template Params<R>;

    // members: N particle indices per bond; params: one per bond. Only bonds whose particles all
    // belong to the scope's group are given (the caller filters).
    BondInteraction(const B& backend, InteractorScope scope, int64_t particles, const std::vector<int>& members,
                    const std::vector<Params>& params)
        : Interactor<B, R>(std::move(scope)), backend_(backend) {
        std::vector<int> first(particles + 1, 0);
        for (int m : members) ++first[m + 1];
        for (int64_t i = 0; i < particles; ++i) first[i + 1] += first[i];
        std::vector<int> entries(members.size());
        std::vector<int> next(first.begin(), first.end() - 1);
        for (size_t k = 0; k < members.size(); ++k) entries[next[members[k]]++] = static_cast<int>(k);
        backend_.upload(firstEntry_, first.data(), first.size());
        backend_.upload(entries_, entries.data(), entries.size());
        backend_.upload(members_, members.data(), members.size());
        backend_.upload(params_, params.data(), params.size());
    }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            backend_.for_each(particles.count,
                              BondKernel<Potential, R, decltype(force)::value, decltype(energy)::value,
                                         decltype(virial)::value>{particles.pos.data(), particles.box,
                                                                  firstEntry_.data(), entries_.data(),
                                                                  members_.data(), params_.data(), out});
        });
    }

private:
    const B& backend_;
    typename B::template Buffer<int> firstEntry_, entries_, members_;
    typename B::template Buffer<Params> params_;
};

}  // namespace structmd
