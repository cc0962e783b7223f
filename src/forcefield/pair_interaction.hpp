#pragma once
// A non-bonded pair term over a Verlet list, generic in its potential (the kernel is in
// pair_kernel.hpp).
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "forcefield/cluster_pair_kernel.hpp"
#include "forcefield/hessian_kernels.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/lambda_coupling.hpp"
#include "forcefield/pair_force_kernels.hpp"
#include "forcefield/pair_kernel.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

template <class B, class R, class Potential, class PairR = R>
class PairInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<PairR>;

    // batch: the particles' batches when the table has one ntypes x ntypes block per batch, else null.
    // radius: the radii a potential of radii reads (backend memory, by particle) when they are not
    // the particles' own (StericInner's innerRadius column); null: the particles' radii.
    PairInteraction(const B& backend, InteractorScope scope, std::shared_ptr<VerletList<B, R>> list,
                    const std::vector<Params>& table, int ntypes, const int* batch = nullptr,
                    const R* radius = nullptr)
        : Interactor<B, R>(std::move(scope)),
          backend_(backend),
          list_(std::move(list)),
          ntypes_(ntypes),
          batch_(batch),
          radius_(radius) {
        backend_.upload(table_, table.data(), table.size());
        if (kCellLocal) list_->keep_cell_local_positions();
    }

    bool pairwise() const override { return true; }

    bool has_pair_forces() const override { return true; }
    void add_pair_forces(Particles<B, R>& particles, int seed, Real4<R>* out) override {
        backend_.for_each(particles.count, PairForceOnSeedKernel<Potential, R, PairR>{
                                               particles.charge.data(), radii(particles), this->group(),
                                               list_->view(), table_of(table_), seed, out});
    }

    // The table again in dual numbers, for the Hessian.
    void enable_hessian(const std::vector<typename Potential::template Params<Dual<PairR>>>& table) {
        hessian_ = true;
        backend_.upload(dualTable_, table.data(), table.size());
    }
    bool has_hessian() const override { return hessian_; }
    void add_hessian(Particles<B, R>& particles, int seed, Tensor3<R>* blocks) override {
        backend_.for_each(particles.count,
                          PairHessianKernel<Potential, R, PairR>{particles.charge.data(), radii(particles),
                                                                 this->group(), list_->view(), table_of(dualTable_),
                                                                 seed, blocks});
    }

    bool couples_to_lambda() const override { return couples_to_lambda_v; }
    void add_lambda_derivative(Particles<B, R>& particles, R* perParticle) override {
        if constexpr (couples_to_lambda_v) {
            const ForceOutputs<R> out = energy_outputs(perParticle);
            backend_.for_each_lanes(particles.count,
                                    PairKernel<PairLambdaDerivative<Potential>, R, PairR, false, true, false>{
                                        particles.charge.data(), radii(particles), this->group(),
                                        kernel_view(), table_of(table_), out});
        }
    }

    void prepare(Particles<B, R>& p) override { list_->update(p.pos, p.count, p.box, p.version); }
    // Each slot's leader writes its particle's sums, for every particle without a group; the cluster
    // kernels add from several tiles.
    bool stores_forces() const override { return !this->group() && !list_->clusters(); }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        if (list_->clusters()) {
            const ClusterView<R> clusters = list_->cluster_view();
            dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
                backend_.for_each_lanes(clusters.clusters,
                                        ClusterPairKernel<Potential, R, PairR, decltype(force)::value,
                                                          decltype(energy)::value, decltype(virial)::value>{
                                            particles.charge.data(), radii(particles), this->group(), clusters,
                                            table_of(table_), out},
                                        LaneSizing::kWarp);
            });
            return;
        }
        const NeighbourView<R> view = kernel_view();
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            using Kernel = PairKernel<Potential, R, PairR, decltype(force)::value, decltype(energy)::value,
                                      decltype(virial)::value>;
            const Kernel kernel{particles.charge.data(), radii(particles), this->group(), view, table_of(table_), out};
            const auto launch = [&](auto plain) {
                constexpr bool kPlain = decltype(plain)::value;
                if (Kernel::kCellLocal && view.cellLocal.local)
                    backend_.for_each_lanes(particles.count, PairKernelWithSeparations<Kernel, Kernel::kCellLocal, kPlain>{kernel});
                else
                    backend_.for_each_lanes(particles.count, PairKernelWithSeparations<Kernel, false, kPlain>{kernel});
            };
            // Forces alone, a step's usual call, have kernels of their own for one type and no group;
            // the energies and virials, read now and then, take the general ones.
            constexpr bool kForcesAlone = decltype(force)::value && !decltype(energy)::value && !decltype(virial)::value;
            if constexpr (kForcesAlone) {
                if (kernel.plain()) {
                    launch(std::true_type{});
                    return;
                }
            }
            launch(std::false_type{});
        });
    }

private:
    const R* radii(const Particles<B, R>& particles) const { return radius_ ? radius_ : particles.radius.data(); }
    template <class P>
    PairTable<P> table_of(const typename B::template Buffer<P>& table) const {
        return PairTable<P>{table.data(), ntypes_, batch_};
    }
    static constexpr bool couples_to_lambda_v = structmd::couples_to_lambda<Potential>::value;
    // Its kernels take separations from cell-local positions where the list keeps them.
    static constexpr bool kCellLocal = PairKernel<Potential, R, PairR, true, false, false>::kCellLocal;
    // The list as its PairKernels read it.
    NeighbourView<R> kernel_view() const { return kCellLocal ? list_->cell_local_view() : list_->view(); }

    const B& backend_;
    std::shared_ptr<VerletList<B, R>> list_;
    typename B::template Buffer<Params> table_;
    typename B::template Buffer<typename Potential::template Params<Dual<PairR>>> dualTable_;
    bool hessian_ = false;
    int ntypes_;
    const int* batch_;
    const R* radius_;
};

}  // namespace structmd
