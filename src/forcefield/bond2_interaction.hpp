#pragma once
// Two-body bonds, generic in their potential. Each particle visits the bonds it takes part in
// (a per-particle index built once at load) and keeps its own share: no atomics, and the same sum
// order on every backend. Energy and virial of a bond are split equally between its two particles.
#include <cstdint>
#include <string>
#include <vector>

#include "forcefield/interactor.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {

template <class Potential, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct Bond2Kernel {
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    Box<R> box;
    const int* firstBond;  // bonds of particle i: bondsOf[firstBond[i] .. firstBond[i+1])
    const int* bondsOf;
    const int* ends;  // particles of bond b: ends[2b], ends[2b+1]
    const Params* params;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        Vec3<R> f{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        for (int k = firstBond[i]; k < firstBond[i + 1]; ++k) {
            const int b = bondsOf[k];
            const int a = ends[2 * b];
            const int c = ends[2 * b + 1];
            const Vec3<R> d = box.minimum_image(xyz(pos[c]) - xyz(pos[a]));
            const PairTerm<R> t = Potential::evaluate(dot(d, d), params[b]);
            if (WantForce) {
                const Vec3<R> fa = t.dudr_over_r * d;
                f += (a == i) ? fa : -fa;
            }
            if (WantEnergy) e += R(0.5) * t.energy;
            if (WantVirial) w += (R(-0.5) * t.dudr_over_r) * outer(d, d);
        }
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w);
    }
};

template <class B, class R, class Potential>
class Bond2Interaction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<R>;

    // ends: 2 particle indices per bond; params: one per bond.
    Bond2Interaction(const B& backend, std::string name, int64_t particles, const std::vector<int>& ends,
                     const std::vector<Params>& params)
        : Interactor<B, R>(std::move(name)), backend_(backend) {
        std::vector<int> first(particles + 1, 0);
        for (int end : ends) ++first[end + 1];
        for (int64_t i = 0; i < particles; ++i) first[i + 1] += first[i];
        std::vector<int> bondsOf(ends.size());
        std::vector<int> fill(first.begin(), first.end() - 1);
        for (size_t k = 0; k < ends.size(); ++k) bondsOf[fill[ends[k]]++] = static_cast<int>(k / 2);
        backend_.upload(firstBond_, first.data(), first.size());
        backend_.upload(bondsOf_, bondsOf.data(), bondsOf.size());
        backend_.upload(ends_, ends.data(), ends.size());
        backend_.upload(params_, params.data(), params.size());
    }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            backend_.for_each(particles.count,
                              Bond2Kernel<Potential, R, decltype(force)::value, decltype(energy)::value,
                                          decltype(virial)::value>{particles.pos.data(), particles.box,
                                                                   firstBond_.data(), bondsOf_.data(),
                                                                   ends_.data(), params_.data(), out});
        });
    }

private:
    const B& backend_;
    typename B::template Buffer<int> firstBond_, bondsOf_, ends_;
    typename B::template Buffer<Params> params_;
};

}  // namespace structmd
