// A structmd plugin: a transverser that counts each particle's neighbours, run by a host as
// structmd_traverse(sim, "NeighbourCount", NULL, cutoff, counts, n). Each particle's number of other
// particles closer than the cutoff (or, for cutoff 0, every other particle of its group and batch).
// Written once for every backend against the Transverser contract (transverser/transverser.hpp);
// built as a .cu file, it also runs on the CUDA backend when structmd was built with CUDA.
#include "engines/plugin.hpp"

namespace {

using namespace structmd;

struct NeighbourCount {
    static constexpr int values = 1;
    static std::vector<Parameter> parameters() { return {}; }

    template <class R>
    struct Functor {
        using Info = int;   // nothing of a particle is needed beyond its position
        using Compute = R;  // a count, summed in R as the output is
        R* out;

        SMD_HD R zero() const { return R(0); }
        SMD_HD int info(int) const { return 0; }
        SMD_HD R compute(const Real4<R>&, const Real4<R>&, int, int) const { return R(1); }
        SMD_HD void accumulate(R& total, const R& current) const { total += current; }
        SMD_HD void set(int i, const R& total) const { out[i] = total; }
    };

    template <class R>
    static Functor<R> make(const TransverserInputs<R>& in, const ParameterValues&) {
        return {in.out};
    }
};

}  // namespace

STRUCTMD_PLUGIN(registrar) { registrar.transverser<NeighbourCount>("NeighbourCount"); }
