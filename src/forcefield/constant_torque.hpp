#pragma once
// ["External","ConstantTorque"]: the same torque constantTorque on every particle (of the entry's
// group), in the lab frame; no force and no energy (the field keeps no account of its work, as
// ["External","ConstantForce"]). Torques act only on orientations, so the term adds nothing to a
// force, a pair force or a Hessian.
#include <array>
#include <memory>
#include <vector>

#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/interactor_build.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

template <class R>
struct AddConstantTorque {
    Real4<R>* torque;
    const uint8_t* group;
    Vec3<R> value;
    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        accumulate(torque[i], value);
    }
};

template <class B, class R>
class ConstantTorqueInteraction : public Interactor<B, R> {
public:
    ConstantTorqueInteraction(const B& backend, InteractorScope scope, const Vec3<R>& torque)
        : Interactor<B, R>(std::move(scope)), backend_(backend), torque_(torque) {}

    bool has_hessian() const override { return true; }
    void add_hessian(Particles<B, R>&, int, Tensor3<R>*) override {}
    bool has_pair_forces() const override { return true; }
    void add_pair_forces(Particles<B, R>&, int, Real4<R>*) override {}

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        if (!out.torque) return;
        backend_.for_each(particles.count, AddConstantTorque<R>{out.torque, this->group(), torque_});
    }

private:
    const B& backend_;
    Vec3<R> torque_;
};

struct ConstantTorqueComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);  // constant_torque_read.cpp

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& external = static_cast<const ExternalSpec&>(s);
        const std::array<double, 3> t = external.values.vec3("constantTorque");
        return std::make_unique<ConstantTorqueInteraction<B, R>>(build.backend, build.scope(external),
                                                                 Vec3<R>{R(t[0]), R(t[1]), R(t[2])});
    }
};

}  // namespace structmd
