#pragma once
// Interaction terms whose potential is C++ source compiled at load time, on a backend that compiles
// kernels at run time (the CUDA backend through NVRTC). The source is instantiated in the same
// kernels as the built-in potentials (pair_kernel.hpp, bond_kernel.hpp, external_kernel.hpp), so a
// potential given as an expression runs as fast as one shipped with the engine.
//
// The host never sees the compiled potential's type: it launches the kernel over an opaque
// potential whose Params is one real. A kernel functor over it has the layout of the functor over
// the compiled potential, whose parameter pointer differs only in the type it points to (and whose
// by-value Params, for an external field, is one real too).
#include <memory>
#include <string>
#include <vector>

#include "forcefield/bond_interaction.hpp"
#include "forcefield/external_kernel.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/pair_kernel.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

// A potential as source: `definition` declares `RuntimePotential`, a potential of the kind the
// term's kernel takes (pair_potential.hpp, bond_potential.hpp or external_potential.hpp, less the
// host-side reading) whose Params<R> are reals only, laid out as the host fills them.
struct RuntimeSource {
    std::string definition;
};

struct OpaquePairPotential {
    template <class R>
    using Params = R;
};

template <int N>
struct OpaqueBondPotential {
    static constexpr int arity = N;
    template <class R>
    using Params = R;
};

struct OpaqueExternalPotential {
    template <class R>
    using Params = R;
};

template <class R>
constexpr const char* real_type_name() {
    return sizeof(R) == sizeof(float) ? "float" : "double";
}

// The kernels of one source, one for each set of outputs (force, energy, virial) compute() may
// be asked for.
template <class B>
class OutputKernels {
public:
    // name(force, energy, virial) is the C++ name of the kernel for those outputs, each flag
    // "true" or "false"; withVirial: whether any kernel computes the virial.
    template <class Name>
    OutputKernels(const B& backend, const std::string& kernelHeader, const RuntimeSource& source, bool withVirial,
                  Name name) {
        std::vector<std::string> names;
        const auto flag = [](int outputs, int bit) { return (outputs & bit) ? "true" : "false"; };
        for (int outputs = 1; outputs < (withVirial ? 8 : 4); ++outputs)
            names.push_back(name(flag(outputs, 1), flag(outputs, 2), flag(outputs, 4)));
        kernels_ = backend.compile("#include \"backends/cuda/launch_kernels.cuh\"\n#include \"" + kernelHeader +
                                       "\"\nusing namespace structmd;\n" + source.definition,
                                   names);
    }

    const void* operator()(bool force, bool energy, bool virial) const {
        return kernels_->kernel(static_cast<size_t>((force ? 1 : 0) | (energy ? 2 : 0) | (virial ? 4 : 0)) - 1);
    }
    double seconds() const { return kernels_->seconds(); }

private:
    typename B::CompiledKernels kernels_;
};

// A non-bonded pair term over a Verlet list.
template <class B, class R, class PairR>
class CompiledPairInteraction : public Interactor<B, R> {
public:
    // table: the Params of each ordered type pair (ntypes x ntypes, one such block per batch when
    // batch is given), cutoff2 first.
    CompiledPairInteraction(const B& backend, InteractorScope scope, std::shared_ptr<VerletList<B, R>> list,
                            const RuntimeSource& source, const std::vector<PairR>& table, int ntypes,
                            const int* batch)
        : Interactor<B, R>(std::move(scope)),
          backend_(backend),
          list_(std::move(list)),
          ntypes_(ntypes),
          batch_(batch),
          kernels_(backend, "forcefield/pair_kernel.hpp", source, true, [](auto F, auto E, auto V) {
              return std::string("&structmd::for_each_lanes_kernel<structmd::PairKernel<RuntimePotential, ") +
                     real_type_name<R>() + ", " + real_type_name<PairR>() + ", " + F + ", " + E + ", " + V + ">>";
          }) {
        backend_.upload(table_, table.data(), table.size());
    }

    double compile_seconds() const { return kernels_.seconds(); }

    bool pairwise() const override { return true; }

    void prepare(Particles<B, R>& p) override { list_->update(p.pos, p.count, p.box, p.version); }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        const NeighbourView<R> view = list_->view();
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            constexpr bool F = decltype(force)::value, E = decltype(energy)::value, V = decltype(virial)::value;
            using Kernel = PairKernel<OpaquePairPotential, R, PairR, F, E, V>;
            backend_.for_each_lanes_compiled(
                kernels_(F, E, V), particles.count,
                Kernel{particles.charge.data(), particles.radius.data(), this->group(), view,
                       PairTable<PairR>{table_.data(), ntypes_, batch_}, out});
        });
    }

private:
    const B& backend_;
    std::shared_ptr<VerletList<B, R>> list_;
    typename B::template Buffer<PairR> table_;
    int ntypes_;
    const int* batch_;
    OutputKernels<B> kernels_;
};

// A bonded term of N particles.
template <class B, class R, int N>
class CompiledBondInteraction : public Interactor<B, R> {
public:
    // members: N particle indices per bond; params: the Params of each bond.
    CompiledBondInteraction(const B& backend, InteractorScope scope, int64_t particles,
                            const std::vector<int>& members, const RuntimeSource& source, const std::vector<R>& params)
        : Interactor<B, R>(std::move(scope)),
          backend_(backend),
          index_(backend, particles, members),
          kernels_(backend, "forcefield/bond_kernel.hpp", source, true, [](auto F, auto E, auto V) {
              return std::string("&structmd::for_each_kernel<structmd::BondKernel<RuntimePotential, ") +
                     real_type_name<R>() + ", " + F + ", " + E + ", " + V + ">>";
          }) {
        backend_.upload(params_, params.data(), params.size());
    }

    double compile_seconds() const { return kernels_.seconds(); }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            constexpr bool F = decltype(force)::value, E = decltype(energy)::value, V = decltype(virial)::value;
            using Kernel = BondKernel<OpaqueBondPotential<N>, R, F, E, V>;
            backend_.for_each_compiled(kernels_(F, E, V), particles.count,
                                       index_.template kernel<Kernel>(particles, params_.data(), out));
        });
    }

private:
    const B& backend_;
    BondIndex<B, N> index_;
    typename B::template Buffer<R> params_;
    OutputKernels<B> kernels_;
};

// A field acting on each particle alone, whose source's Params<R> is one real.
template <class B, class R>
class CompiledExternalInteraction : public Interactor<B, R> {
public:
    CompiledExternalInteraction(const B& backend, InteractorScope scope, const RuntimeSource& source, R param)
        : Interactor<B, R>(std::move(scope)),
          backend_(backend),
          param_(param),
          kernels_(backend, "forcefield/external_kernel.hpp", source, false, [](auto F, auto E, auto) {
              return std::string("&structmd::for_each_kernel<structmd::ExternalKernel<RuntimePotential, ") +
                     real_type_name<R>() + ", " + F + ", " + E + ", false>>";
          }) {}

    double compile_seconds() const { return kernels_.seconds(); }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        ForceOutputs<R> own = out;
        own.virial = nullptr;
        dispatch_outputs(own, [&](auto force, auto energy, auto) {
            constexpr bool F = decltype(force)::value, E = decltype(energy)::value;
            using Kernel = ExternalKernel<OpaqueExternalPotential, R, F, E, false>;
            backend_.for_each_compiled(kernels_(F, E, false), particles.count,
                                       Kernel{particles.pos.data(), particles.radius.data(), this->group(), param_,
                                              particles.now(), own});
        });
    }

private:
    const B& backend_;
    R param_;
    OutputKernels<B> kernels_;
};

}  // namespace structmd
