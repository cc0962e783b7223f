#pragma once
// Bonded terms of N = 1..4 particles, generic in their potential (bond_potential.hpp), over the
// per-particle index of their bonds (bond_kernel.hpp) built once at load.
#include <cstdint>
#include <string>
#include <vector>

#include "forcefield/bond_kernel.hpp"
#include "forcefield/bond_potential.hpp"
#include "forcefield/hessian_kernels.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/lambda_coupling.hpp"
#include "forcefield/pair_force_kernels.hpp"

namespace structmd {

// Which bonds of N particles each particle takes part in, in backend memory, as BondKernel reads them.
template <class B, int N>
struct BondIndex {
    typename B::template Buffer<int> firstEntry;
    typename B::template Buffer<BondEntry<N>> entries;

    // members: N particle indices per bond.
    BondIndex(const B& backend, int64_t particles, const std::vector<int>& bondMembers) {
        std::vector<int> first(particles + 1, 0);
        for (int m : bondMembers) ++first[m + 1];
        for (int64_t i = 0; i < particles; ++i) first[i + 1] += first[i];
        std::vector<BondEntry<N>> entryOf(bondMembers.size());
        std::vector<int> next(first.begin(), first.end() - 1);
        for (size_t k = 0; k < bondMembers.size(); ++k) {
            BondEntry<N>& entry = entryOf[next[bondMembers[k]]++];
            entry.bondSlot = static_cast<int>(k);
            const size_t bond = k / N;
            for (int m = 0; m < N; ++m) entry.member[m] = bondMembers[bond * N + m];
        }
        backend.upload(firstEntry, first.data(), first.size());
        backend.upload(entries, entryOf.data(), entryOf.size());
    }

    template <class Kernel, class R>
    Kernel kernel(const Particles<B, R>& particles, const typename Kernel::Params* params,
                  const ForceOutputs<R>& out) const {
        return Kernel{particles.pos.data(), particles.box, firstEntry.data(), entries.data(), params, out};
    }

    template <class R, class Params>
    BondsAroundSeed<N, R, Params> around(const Particles<B, R>& particles, const Params* params, int seed) const {
        return {particles.pos.data(), particles.box, firstEntry.data(), entries.data(), params, seed};
    }
};

template <class B, class R, class Potential>
class BondInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<R>;

    // members: N particle indices per bond; params: one per bond. Only bonds whose particles all
    // belong to the scope's group are given (the caller filters).
    BondInteraction(const B& backend, InteractorScope scope, int64_t particles, const std::vector<int>& members,
                    const std::vector<Params>& params)
        : Interactor<B, R>(std::move(scope)), backend_(backend), index_(backend, particles, members) {
        backend_.upload(params_, params.data(), params.size());
    }

    bool has_pair_forces() const override { return true; }
    void add_pair_forces(Particles<B, R>& particles, int seed, Real4<R>* out) override {
        if constexpr (Potential::arity > 1)
            backend_.for_each(particles.count, BondForceOnSeedKernel<Potential, R>{
                                                   index_.around(particles, params_.data(), seed), out});
    }

    // The parameters again in dual numbers (one per bond, as given to the constructor), for the Hessian.
    void enable_hessian(const std::vector<typename Potential::template Params<Dual<R>>>& params) {
        hessian_ = true;
        backend_.upload(dualParams_, params.data(), params.size());
    }
    bool has_hessian() const override { return hessian_; }
    void add_hessian(Particles<B, R>& particles, int seed, Tensor3<R>* blocks) override {
        backend_.for_each(particles.count,
                          BondHessianKernel<Potential, R>{
                              index_.around(particles, dualParams_.data(), seed), blocks});
    }

    bool couples_to_lambda() const override { return couples_to_lambda_v; }
    void add_lambda_derivative(Particles<B, R>& particles, R* perParticle) override {
        if constexpr (couples_to_lambda_v) {
            const ForceOutputs<R> out = energy_outputs(perParticle);
            using Kernel = BondKernel<BondLambdaDerivative<Potential>, R, false, true, false>;
            backend_.for_each(particles.count, index_.template kernel<Kernel>(particles, params_.data(), out));
        }
    }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            using Kernel = BondKernel<Potential, R, decltype(force)::value, decltype(energy)::value,
                                      decltype(virial)::value>;
            backend_.for_each(particles.count, index_.template kernel<Kernel>(particles, params_.data(), out));
        });
    }

private:
    static constexpr int arity = Potential::arity;
    static constexpr bool couples_to_lambda_v = structmd::couples_to_lambda<Potential>::value;

    const B& backend_;
    BondIndex<B, arity> index_;
    typename B::template Buffer<Params> params_;
    typename B::template Buffer<typename Potential::template Params<Dual<R>>> dualParams_;
    bool hessian_ = false;
};

}  // namespace structmd
