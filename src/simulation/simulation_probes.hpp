#pragma once
// What simulation steps probe beyond the state (Simulation::probes()): one term's arrays, Hessian
// columns, pair forces, forces at a displaced particle, dU/dlambda. Vectors are 3n doubles in
// particle-id order.
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "simulation/expression_transverser.hpp"
#include "simulation/transverser_call.hpp"

namespace structmd {

class SimulationProbes {
public:
    virtual ~SimulationProbes() = default;

    // One forceField entry's energy on each particle (split as the per-particle energies split it),
    // its force on each (3n) and its torque on each (3n, lab frame; zero for terms that do not act
    // on orientations), in id order; zero while the entry is inactive. ERR_ARGUMENT for a name that
    // is not an entry.
    virtual void term_energies_and_forces(const std::string& term, double* energies, double* forces,
                                          double* torques) = 0;
    // The Hessian of the force field's potential energy (its terms only: no external forces, no
    // callbacks), one column of 3x3 blocks at a time: for particle `id`, blocks[9 j + 3 a + b] =
    // d2U / dx_id^a dx_j^b for every particle j, in id order. Exact second derivatives; only for an
    // input whose steps ask for them (SimulationStep::needs_hessian), else ERR_STATE.
    virtual void hessian_column(int64_t id, double* blocks) = 0;
    // The forces each particle j exerts on particle `id` through the force field's terms (as
    // hessian_column), 3n in id order: pair forces, and bonds split into central pair forces; fields
    // and tethers of one particle exert none. Only for an input whose steps ask for them
    // (SimulationStep::needs_pair_forces), else ERR_STATE.
    virtual void pair_forces_on(int64_t id, double* f) = 0;
    // The forces of the force field's terms alone (as hessian_column) with particle `id` displaced by
    // `displacement`, in id order (3n); the state is as it was afterwards.
    virtual void forces_with_displaced(int64_t id, const double displacement[3], double* f) = 0;
    // dU/dlambda summed over the active terms of lambda (0 without any).
    virtual double lambda_derivative() = 0;
    // Each particle's sum of an expression transverser (transverser/expression_sum.hpp) over its pairs,
    // in id order (n values); particles outside the spec's group get 0. The engine prepares a spec's
    // traversal (its list, its kernel) at the first call with its key and reuses it after.
    virtual void expression_sum(const ExpressionTransverserSpec& spec, double* perParticle) {
        (void)perParticle;
        throw Error(STRUCTMD_ERR_UNSUPPORTED, spec.path + ": expression transversers run on one engine, not under "
                                                          "this parallel layout");
    }
    // A registered transverser's numbers (call.values per particle), in id order (call.values x n);
    // particles outside the call's group get 0. The engine keeps the neighbour list of each cutoff.
    virtual void traverse(const TransverserCall& call, double* perParticle) {
        (void)perParticle;
        throw Error(STRUCTMD_ERR_UNSUPPORTED, "transverser '" + call.name + "': transversers run on one engine, "
                                              "not under this parallel layout");
    }
    // The same left on the backend: the engine's output array of the run, call.values x n reals in id
    // order, with the backend's work finished. It stays the engine's, valid until the next run of a
    // registered transverser or anything that changes the engine's state.
    struct TransverserOutput {
        const void* data;
        int64_t n;     // particles
        int values;    // per particle
        int realSize;  // bytes of one real
        int device;    // the CUDA device, or -1 for host memory
    };
    virtual TransverserOutput traverse_on_backend(const TransverserCall& call) {
        throw Error(STRUCTMD_ERR_UNSUPPORTED, "transverser '" + call.name + "': transversers run on one engine, "
                                              "not under this parallel layout");
    }
    // The bonds of a ["PatchyParticles","DynamicallyBondedPatchyParticles"] entry: for each of its
    // patches (in the order of patchesState), the patch it is bonded to, or -1. They are the bonds the
    // last force evaluation acted with (reading them settles nothing). ERR_ARGUMENT for a name that is
    // not such an entry.
    virtual std::vector<int> patch_bonds(const std::string& entry) {
        throw Error(STRUCTMD_ERR_UNSUPPORTED, "forceField entry '" + entry +
                                                  "': patch bonds are read on one engine, not under this parallel layout");
    }
    // Whether the particles carry magnetic moments (the magnetic trajectory formats and measures).
    virtual bool has_magnetization() const = 0;
};

}  // namespace structmd
