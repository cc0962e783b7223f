#pragma once
// UAMMD-structured's ["Surface","Absorbed"]: the particles (of the entry's group) that start below the
// height heightThreshold (the state's z) stick where they are: each is tied to its starting position p
// by the spring of ["Bond1","FixedHarmonic"] with r0 = 0,
//   U = K/2 |d|^2,   F = K d,   d = wrap(p - r),
// and the others feel nothing. The reader (absorbed_read.cpp) picks the particles once, from the
// state, as UAMMD-structured does at its first evaluation.
#include <memory>
#include <vector>

#include "forcefield/bond_interaction.hpp"
#include "forcefield/fixed_harmonic.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor_build.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from the entry: the particles absorbed and where.
struct AbsorbedConfig : ComponentConfig {
    double K = 0.0;
    std::vector<int> ids;
    std::vector<Vec3<double>> anchors;
};

struct AbsorbedComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);  // absorbed_read.cpp

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& config = static_cast<const AbsorbedConfig&>(*s.config);
        const std::vector<uint8_t>* inGroup = s.group >= 0 ? &build.spec.groups[s.group].members : nullptr;
        std::vector<int> members;
        std::vector<size_t> anchors;
        for (size_t k = 0; k < config.ids.size(); ++k)
            if (!inGroup || (*inGroup)[config.ids[k]]) {
                members.push_back(config.ids[k]);
                anchors.push_back(k);
            }
        // The tethers in real type T (R, or its dual numbers for the Hessian).
        const auto tethers = [&](auto real) {
            using T = decltype(real);
            std::vector<FixedHarmonic::Params<T>> params;
            for (size_t k : anchors) {
                const Vec3<double>& p = config.anchors[k];
                params.push_back({T(config.K), T(0), {T(p.x), T(p.y), T(p.z)}});
            }
            return params;
        };
        auto interactor = std::make_unique<BondInteraction<B, R, FixedHarmonic>>(
            build.backend, build.scope(s), build.context.particles, members, tethers(R{}));
        if (build.context.hessian) interactor->enable_hessian(tethers(Dual<R>{}));
        return interactor;
    }
};

}  // namespace structmd
