#pragma once
// An expression transverser (transverser/expression_sum.hpp) made ready on one backend: its
// neighbour list (for a cutoff) and its expression, interpreted from uploaded bytecode on the CPU
// backend or compiled into the traversal's kernel at the first run on a backend that compiles at
// run time (CUDA), as the Expression potentials are (forcefield/expression_component.hpp).
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "forcefield/compiled_interaction.hpp"
#include "forcefield/expression_compiled.hpp"
#include "forcefield/expression_component.hpp"
#include "forcefield/expression_potentials.hpp"
#include "forcefield/interactor_build.hpp"
#include "neighbour/verlet_list.hpp"
#include "simulation/expression_transverser.hpp"
#include "state/particles.hpp"
#include "transverser/all_pairs_traversal.hpp"
#include "transverser/expression_sum.hpp"
#include "transverser/neighbour_traversal.hpp"

namespace structmd {

// The Params of the compiled expression as the host sees them: compiled_expression_source gives an
// expression without data columns one unused real.
struct OpaqueSumFunction {
    template <class R>
    struct Params {
        R columns[1];
    };
};

// The backend's compiled kernels where it compiles at run time; nothing (an int) on the others.
template <class B, class = void>
struct CompiledKernelsOf {
    using type = int;
};
template <class B>
struct CompiledKernelsOf<B, std::void_t<typename B::CompiledKernels>> {
    using type = typename B::CompiledKernels;
};

template <class B, class R>
class PreparedExpressionSum {
public:
    PreparedExpressionSum(const B& backend, const ExpressionTransverserSpec& spec, const ForceFieldContext& context)
        : backend_(backend), spec_(spec), batch_(context.batch) {
        if constexpr (B::compiles_at_run_time) {
            const ExpressionSumKernels source = expression_sum_kernels(spec, real_type_name<R>());
            kernels_ = backend.compile(source.source, source.names);
            if (context.log) log_compile_time(context.log, spec.path, kernels_->seconds());
        } else {
            program_ = upload_program<B, R>(backend, spec.program);
        }
    }

    // Each particle's sum into output() (0 outside the group), for the current positions. list: one
    // that offers every pair within spec.cutoff (Engine::transverser_list), asked for at each run
    // since the force field's lists change when it is made again; null for all pairs. adaptList:
    // whether this run adapts it afterwards (a list of the transversers' own).
    void run(Particles<B, R>& p, const uint8_t* group, VerletList<B, R>* list, bool adaptList) {
        backend_.resize(out_, p.count);
        // Without a group every particle's set writes its sum, so only a group needs the zeros.
        if (group) backend_.fill(out_, R(0));
        if (p.count == 0) return;
        if constexpr (B::compiles_at_run_time) {
            traverse<OpaqueSumFunction>(p, group, list, OpaqueSumFunction::Params<R>{{R(0)}});
        } else {
            typename InterpretedExpression::template Params<R> params{};
            params.program = program_->view();
            traverse<InterpretedExpression>(p, group, list, params);
        }
        if (list && adaptList) list->adapt();
    }

    const typename B::template Buffer<R>& output() const { return out_; }

private:
    template <class Function>
    void traverse(Particles<B, R>& p, const uint8_t* group, VerletList<B, R>* list,
                  const typename Function::template Params<R>& params) {
        const ExpressionSum<Function, R> sum{params, p.charge.empty() ? nullptr : p.charge.data(),
                                             p.radius.empty() ? nullptr : p.radius.data(),
                                             p.vel.empty() ? nullptr : p.vel.data(), out_.data()};
        if (list) {
            list->update(p.pos, p.count, p.box, p.version);
            const NeighbourTraversal<ExpressionSum<Function, R>, R> traversal{sum, list->view(),
                                                                              R(spec_.cutoff * spec_.cutoff), group};
            launch(0, p.count, traversal);
        } else {
            size_t kernel = 1;
            if constexpr (B::compiles_at_run_time)
                if (all_pairs_in_tiles(backend_, p.count)) kernel = 2;
            launch(kernel, p.count,
                   AllPairsTraversal<ExpressionSum<Function, R>, R>{sum, p.pos.data(), p.count, p.box, group, batch_});
        }
    }

    template <class F>
    void launch(size_t kernel, int64_t n, const F& f) {
        if constexpr (B::compiles_at_run_time)
            backend_.for_each_lanes_compiled(kernels_->kernel(kernel), n, f);
        else
            backend_.for_each_lanes(n, f);
    }

    const B& backend_;
    ExpressionTransverserSpec spec_;
    const int* batch_;  // the particles' batches, numbered 0, 1, ... (null: one batch)
    std::shared_ptr<UploadedProgram<B, R>> program_;
    typename CompiledKernelsOf<B>::type kernels_{};
    typename B::template Buffer<R> out_;
};

}  // namespace structmd
