#pragma once
// A field acting on each particle alone (external_potential.hpp), generic in its potential, run by
// the kernels of external_kernel.hpp: one Params for every particle, or one per type.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "forcefield/external_kernel.hpp"
#include "forcefield/hessian_kernels.hpp"
#include "forcefield/external_potential.hpp"
#include "forcefield/interactor.hpp"

namespace structmd {

template <class B, class R, class Potential>
class ExternalInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<R>;

    ExternalInteraction(const B& backend, InteractorScope scope, const Params& params)
        : Interactor<B, R>(std::move(scope)), backend_(backend), params_(params) {}

    // A field exerts no force from another particle.
    bool has_pair_forces() const override { return true; }
    void add_pair_forces(Particles<B, R>&, int, Real4<R>*) override {}

    // The parameters again in dual numbers, for the Hessian.
    void enable_hessian(const typename Potential::template Params<Dual<R>>& params) { dualParams_ = params; }
    bool has_hessian() const override { return dualParams_.has_value(); }
    void add_hessian(Particles<B, R>& particles, int seed, Tensor3<R>* blocks) override {
        backend_.for_each(1, ExternalHessianKernel<Potential, R>{particles.pos.data(), particles.radius.data(),
                                                                 this->group(), *dualParams_, particles.now(), seed,
                                                                 blocks});
    }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        ForceOutputs<R> own = out;
        own.virial = nullptr;
        dispatch_outputs(own, [&](auto force, auto energy, auto) {
            backend_.for_each(particles.count,
                              ExternalKernel<Potential, R, decltype(force)::value, decltype(energy)::value, false>{
                                  particles.pos.data(), particles.radius.data(), this->group(), params_,
                                  particles.now(), own});
        });
    }

private:
    const B& backend_;
    Params params_;
    std::optional<typename Potential::template Params<Dual<R>>> dualParams_;
};

// A field of per-type parameters: `table` and `listed` hold one entry per type, or per (batch, type)
// when `batch` (the batch of each particle, backend memory) is given.
template <class B, class R, class Potential>
class TypedExternalInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<R>;

    TypedExternalInteraction(const B& backend, InteractorScope scope, const std::vector<Params>& table,
                             const std::vector<uint8_t>& listed, const int* batch, int ntypes)
        : Interactor<B, R>(std::move(scope)), backend_(backend), batch_(batch), ntypes_(ntypes) {
        backend_.upload(table_, table.data(), table.size());
        backend_.upload(listed_, listed.data(), listed.size());
    }

    // A field exerts no force from another particle.
    bool has_pair_forces() const override { return true; }
    void add_pair_forces(Particles<B, R>&, int, Real4<R>*) override {}

    // The table again in dual numbers (laid out as `table`), for the Hessian.
    void enable_hessian(const std::vector<typename Potential::template Params<Dual<R>>>& table) {
        backend_.upload(dualTable_, table.data(), table.size());
        hessian_ = true;
    }
    bool has_hessian() const override { return hessian_; }
    void add_hessian(Particles<B, R>& particles, int seed, Tensor3<R>* blocks) override {
        backend_.for_each(1, TypedExternalHessianKernel<Potential, R>{field(particles, dualTable_), seed, blocks});
    }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        ForceOutputs<R> own = out;
        own.virial = nullptr;
        dispatch_outputs(own, [&](auto force, auto energy, auto) {
            backend_.for_each(particles.count,
                              TypedExternalKernel<Potential, R, decltype(force)::value, decltype(energy)::value>{
                                  field(particles, table_), own});
        });
    }

private:
    template <class Entry>
    TypedField<R, Entry> field(const Particles<B, R>& particles,
                               const typename B::template Buffer<Entry>& table) const {
        return {particles.pos.data(), particles.radius.data(), this->group(), table.data(),
                listed_.data(),       batch_,                  ntypes_,       particles.now()};
    }

    const B& backend_;
    typename B::template Buffer<Params> table_;
    typename B::template Buffer<uint8_t> listed_;
    const int* batch_;
    int ntypes_;
    typename B::template Buffer<typename Potential::template Params<Dual<R>>> dualTable_;
    bool hessian_ = false;
};

}  // namespace structmd
