#pragma once
// ["LongRange","Electrostatics"]: the periodic electrostatics of Gaussian charges of width w (point
// charges for w = 0), as UAMMD's spectral Ewald Poisson solver defines them: particle i carries the
// charge density q_i exp(-|x - r_i|^2 / 2w^2) / (2 pi w^2)^(3/2), and the energy is the Coulomb
// energy of that density in the periodic box, with k_e = f / eps_r (f the units' electric conversion
// factor, eps_r the dielectricConstant),
//   U = (2 pi k_e / V) sum_{k != 0} |sum_i q_i exp(i k.r_i)|^2 exp(-k^2 w^2) / k^2  -  sum_i q_i^2 k_e / (2 sqrt(pi) w),
// the k = 0 term left out (a neutralising background) and each charge's energy with itself removed.
// Two Gaussian charges at distance r alone in space interact through k_e q_i q_j erf(r / 2w) / r.
//
// It is summed the Ewald way: the mesh (pme_mesh.hpp) carries Gaussians of a wider width s, and a
// pair term over a neighbour list (ewald_near_field.hpp) the difference of the two kernels, cut where
// it falls below the tolerance. s = w needs no pair term. electrostatics_read.cpp chooses s, the
// cutoff and the grid from the entry.
#include <memory>
#include <vector>

#include "forcefield/ewald_near_field.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/pair_interaction.hpp"
#include "forcefield/pme_mesh.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from the entry.
struct ElectrostaticsConfig : ComponentConfig {
    PmePlan mesh;
    double gaussianWidth = 0.0;  // w
    double nearCutoff = 0.0;     // of the pair term; 0: none (s = w)
};

// The two parts of one entry, evaluated together as one energy term.
template <class B, class R, class PairR>
class ElectrostaticsInteraction : public Interactor<B, R> {
public:
    ElectrostaticsInteraction(const InteractorBuild<B, R>& build, InteractorScope scope, const ElectrostaticsConfig& c)
        : Interactor<B, R>(scope), mesh_(build.backend, c.mesh) {
        if (c.nearCutoff > 0.0) {
            const EwaldNearField::Params<PairR> params{
                PairR(c.mesh.prefactor), PairR(0.5 / c.mesh.farWidth),
                PairR(c.gaussianWidth > 0.0 ? 0.5 / c.gaussianWidth : 0.0), PairR(c.nearCutoff * c.nearCutoff)};
            const int ntypes = static_cast<int>(build.context.ntypes);
            const std::vector<EwaldNearField::Params<PairR>> table(size_t(ntypes) * ntypes, params);
            // Every pair of charges interacts: a list of its own, without exclusions.
            auto list = std::make_shared<VerletList<B, R>>(build.backend, c.nearCutoff, 1.1, PairCondition::all,
                                                           PairFilterInputs{}, build.context.batch,
                                                           build.context.batches, build.context.model);
            build.forceField.add_list(list);
            near_ = std::make_unique<PairInteraction<B, R, EwaldNearField, PairR>>(build.backend, std::move(scope),
                                                                                   list, table, ntypes);
        }
    }

    void prepare(Particles<B, R>& p) override {
        if (near_) near_->prepare(p);
    }

    void compute(Particles<B, R>& p, const ForceOutputs<R>& out) override {
        if (near_) near_->compute(p, out);
        mesh_.compute(p, this->group(), out, this->name());
    }

private:
    std::unique_ptr<PairInteraction<B, R, EwaldNearField, PairR>> near_;
    PmeMesh<B, R> mesh_;
};

struct Electrostatics {
    static ForceFieldComponent reader_entry(ComponentKey key);

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        return std::make_unique<ElectrostaticsInteraction<B, R, PairR>>(
            build, build.scope(s), static_cast<const ElectrostaticsConfig&>(*s.config));
    }
};

}  // namespace structmd
