#pragma once
// A non-bonded pair term whose potential is C++ source compiled at load time, on a backend that
// compiles kernels at run time (the CUDA backend through NVRTC). The source is instantiated in the
// same traversal as the built-in potentials (pair_kernel.hpp), so a potential given as an
// expression runs as fast as one shipped with the engine.
#include <memory>
#include <string>
#include <vector>

#include "forcefield/interactor.hpp"
#include "forcefield/pair_kernel.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

// A pair potential as source. `definition` declares
//   struct RuntimePotential {
//       template <class R> struct Params { R cutoff2; ... };   // `width` reals in all
//       template <class R> static SMD_HD PairTerm<R> evaluate(R r2, const Params<R>& p);
//   };
// and a parameter table holds `width` reals per ordered type pair in that layout.
struct RuntimePairPotential {
    std::string definition;
    size_t width = 0;
};

// The host's view of a runtime potential: its parameters are reals read by the compiled kernel
// only. A PairKernel over it has the layout of the PairKernel over the compiled potential, whose
// table pointer differs only in the type it points to.
struct OpaquePairPotential {
    template <class R>
    using Params = R;
};

template <class R>
constexpr const char* real_type_name() {
    return sizeof(R) == sizeof(float) ? "float" : "double";
}

template <class B, class R, class PairR>
class CompiledPairInteraction : public Interactor<B, R> {
public:
    // table: potential.width reals per ordered type pair (ntypes x ntypes).
    CompiledPairInteraction(const B& backend, InteractorScope scope, std::shared_ptr<VerletList<B, R>> list,
                            const RuntimePairPotential& potential, const std::vector<PairR>& table, int ntypes)
        : Interactor<B, R>(std::move(scope)), backend_(backend), list_(std::move(list)), ntypes_(ntypes) {
        std::vector<std::string> kernels;
        for (int outputs = 1; outputs < 8; ++outputs) kernels.push_back(kernel_name(outputs));
        kernels_ = backend_.compile("#include \"backends/cuda/launch_kernels.cuh\"\n"
                                    "#include \"forcefield/pair_kernel.hpp\"\n"
                                    "using namespace structmd;\n" +
                                        potential.definition,
                                    kernels);
        backend_.upload(table_, table.data(), table.size());
    }

    double compile_seconds() const { return kernels_->seconds(); }

    bool pairwise() const override { return true; }

    void prepare(Particles<B, R>& p) override { list_->update(p.pos, p.count, p.box, p.version); }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        const NeighbourView<R> view = list_->view();
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            constexpr bool F = decltype(force)::value, E = decltype(energy)::value, V = decltype(virial)::value;
            using Kernel = PairKernel<OpaquePairPotential, R, PairR, F, E, V>;
            backend_.for_each_lanes_compiled(
                kernels_->kernel(output_mask(F, E, V) - 1), particles.count,
                Kernel{particles.pos.data(), particles.charge.data(), this->group(), view, table_.data(), ntypes_, out});
        });
    }

private:
    static int output_mask(bool force, bool energy, bool virial) {
        return (force ? 1 : 0) | (energy ? 2 : 0) | (virial ? 4 : 0);
    }
    static std::string kernel_name(int outputs) {
        const auto flag = [&](int bit) { return (outputs & bit) ? "true" : "false"; };
        return std::string("&structmd::for_each_lanes_kernel<structmd::PairKernel<RuntimePotential, ") +
               real_type_name<R>() + ", " + real_type_name<PairR>() + ", " + flag(1) + ", " + flag(2) + ", " +
               flag(4) + ">>";
    }

    const B& backend_;
    std::shared_ptr<VerletList<B, R>> list_;
    typename B::template Buffer<PairR> table_;
    int ntypes_;
    typename B::CompiledKernels kernels_;
};

}  // namespace structmd
