#pragma once
// An interaction term of the force field. compute() adds the term's contribution to whichever
// outputs are requested (a null pointer means "not wanted"), so energies and virials cost nothing on
// steps where nobody reads them.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/vec.hpp"
#include "forcefield/force_outputs.hpp"
#include "state/particles.hpp"

namespace structmd {

// dispatch_wanted (force_outputs.hpp) for the outputs that out holds.
template <class R, class Launch>
void dispatch_outputs(const ForceOutputs<R>& out, Launch&& launch) {
    dispatch_wanted(out.force != nullptr, out.energy != nullptr, out.virial != nullptr, std::forward<Launch>(launch));
}

// Where and when an interactor acts: active for startStep <= step < endStep, on the particles whose
// group byte is 1 (no mask: all particles).
struct InteractorScope {
    std::string name;
    int64_t startStep = 0;
    int64_t endStep = INT64_MAX;
    const uint8_t* group = nullptr;  // backend array by particle
};

template <class B, class R>
class Interactor {
public:
    explicit Interactor(InteractorScope scope) : scope_(std::move(scope)) {}
    virtual ~Interactor() = default;
    Interactor(const Interactor&) = delete;
    Interactor& operator=(const Interactor&) = delete;

    // The forceField entry name; also the energy term's name.
    const std::string& name() const { return scope_.name; }
    bool active(int64_t step) const { return step >= scope_.startStep && step < scope_.endStep; }
    const uint8_t* group() const { return scope_.group; }
    // True for non-bonded pair terms (the per-particle stress measure sums only these).
    virtual bool pairwise() const { return false; }
    // Brings what compute() needs up to date for the present positions (a neighbour list).
    virtual void prepare(Particles<B, R>&) {}
    virtual void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) = 0;
    // Whether compute(), for the layout prepare() left, writes every particle's force exactly once
    // through add_to_outputs, so that it can be handed ForceOutputs::storeForce.
    virtual bool stores_forces() const { return false; }

    // Exact second derivatives (hessian_kernels.hpp), made only for an input that measures them:
    // whether this term has them, and its share of the Hessian column of particle `seed`, added to
    // blocks (by particle). Terms of expressions, tables and plugins have none.
    virtual bool has_hessian() const { return false; }
    virtual void add_hessian(Particles<B, R>&, int, Tensor3<R>*) {
        throw Error(STRUCTMD_ERR_INTERNAL, name() + ": a term without second derivatives was asked for them");
    }

    // The forces other particles exert through this term on particle `seed` (pair_force_kernels.hpp),
    // added to out (by particle): whether the term can split its forces so, and the split. A term of
    // one particle (a field, a tether) exerts none.
    virtual bool has_pair_forces() const { return false; }
    virtual void add_pair_forces(Particles<B, R>&, int, Real4<R>*) {
        throw Error(STRUCTMD_ERR_INTERNAL, name() + ": a term without pair forces was asked for them");
    }

    // Terms of the ensemble's lambda (lambda_coupling.hpp): whether this is one, and its dU/dlambda
    // added to perParticle (by particle, split among the particles of each pair or bond as energies are).
    virtual bool couples_to_lambda() const { return false; }
    virtual void add_lambda_derivative(Particles<B, R>&, R*) {}

    // Terms that add the magnetic field they make to ForceOutputs::magneticField (magnetic fields,
    // dipoles), which the magnetic integrators ask for on its own.
    virtual bool makes_magnetic_field() const { return false; }

    // Keeps alive backend data that the term's parameters point into (a compiled expression, a
    // table's coefficients) for as long as the interactor lives.
    void own(std::shared_ptr<const void> data) { owned_.push_back(std::move(data)); }

private:
    InteractorScope scope_;
    std::vector<std::shared_ptr<const void>> owned_;
};

}  // namespace structmd
