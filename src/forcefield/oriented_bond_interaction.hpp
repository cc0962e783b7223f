#pragma once
// Two-particle bonds that read the particles' orientations (Particles::dir) and exert torques as well
// as forces: ["Bond2","RAP"], ["Bond2","HarmonicRAP"]. Their functor has
//   static constexpr int arity = 2;
//   template <class R> struct Params { ... };
//   static std::vector<Parameter> parameters();
//   template <class R> static Params<R> make_params(const ParameterValues& v, const Constants& c);
//   template <class R> static SMD_HD R compute(const Vec3<R>* r, const Real4<R>* q, const Params<R>& p,
//                                              Vec3<R>* force, Vec3<R>* torque);
// r as for bond_potential.hpp (r[1] the minimum image of the second particle relative to the first),
// q the two orientations; it writes each particle's force and lab-frame torque and returns the energy.
// The same per-particle traversal as bond_kernel.hpp: each particle keeps its own share, energy and
// virial split equally. Second derivatives and pair splits are not made for these terms (their forces
// depend on orientations, which a position Hessian leaves out), so the interactor declares none.
#include <vector>

#include "forcefield/bond_interaction.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/interactor_tables.hpp"

namespace structmd {

template <class Potential, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct OrientedBondKernel {
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    const Real4<R>* dir;
    Box<R> box;
    const int* firstEntry;
    const BondEntry<2>* entries;
    const Params* params;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        Vec3<R> f{0, 0, 0}, t{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        for (int k = firstEntry[i]; k < firstEntry[i + 1]; ++k) {
            const BondEntry<2> entry = entries[k];
            const int slot = entry.bondSlot % 2;
            Vec3<R> r[2];
            bond_positions(pos, box, entry, r);
            const Real4<R> q[2] = {dir[entry.member[0]], dir[entry.member[1]]};
            Vec3<R> force[2], torque[2];
            const R energy = Potential::compute(r, q, params[entry.bondSlot / 2], force, torque);
            if (WantForce) f += force[slot];
            if (WantForce && out.torque) t += torque[slot];
            if (WantEnergy) e += R(0.5) * energy;
            if (WantVirial) w += R(0.5) * outer(r[1] - r[0], force[1]);
        }
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w, t);
    }
};

template <class B, class R, class Potential>
class OrientedBondInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<R>;

    // members: two particle indices per bond, params: one per bond, both of bonds within the group.
    OrientedBondInteraction(const B& backend, InteractorScope scope, int64_t particles, const std::vector<int>& members,
                            const std::vector<Params>& params)
        : Interactor<B, R>(std::move(scope)), backend_(backend), index_(backend, particles, members) {
        backend_.upload(params_, params.data(), params.size());
    }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        // Torques are wanted only with forces (force_cache.hpp: one pass makes both).
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            backend_.for_each(particles.count,
                              OrientedBondKernel<Potential, R, decltype(force)::value, decltype(energy)::value,
                                                 decltype(virial)::value>{
                                  particles.pos.data(), particles.dir.data(), particles.box,
                                  index_.firstEntry.data(), index_.entries.data(),
                                  params_.data(), out});
        });
    }

private:
    const B& backend_;
    BondIndex<B, 2> index_;
    typename B::template Buffer<Params> params_;
};

// The engine side of an oriented bond entry (a configurable component's make_interactor).
template <class Potential, class B, class R>
std::unique_ptr<Interactor<B, R>> make_oriented_bond_interaction(const InteractorBuild<B, R>& build,
                                                                 const InteractionSpec& s) {
    const auto& bond = static_cast<const BondSpec&>(s);
    const Constants& constants = build.context.constants;
    const auto bonds = bonds_in_group<typename Potential::template Params<R>>(
        build, bond, [&](const ParameterValues& v) { return Potential::template make_params<R>(v, constants); });
    return std::make_unique<OrientedBondInteraction<B, R, Potential>>(build.backend, build.scope(bond),
                                                                      build.context.particles, bonds.members,
                                                                      bonds.params);
}

}  // namespace structmd
