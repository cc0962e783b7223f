#pragma once
// ["External","ConstantMagneticField"] and ["External","ACMagneticField"]: a uniform field
// B(t) = b0 a(t) direction, with a = 1 for the constant field and a(t) = sin(2 pi f t + phase) for the
// alternating one, acting on each particle's magnetic moment mu (magnetic_moment.hpp): Zeeman energy
// U = -mu . B, torque mu x B, no force (the field is uniform). The magnetic integrators read B itself.
#include <array>
#include <memory>

#include "forcefield/bonded_geometry.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/magnetic_moment.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

template <class R>
struct MagneticFieldTerm {
    const Real4<R>* magnetization;
    const Real4<R>* dir;  // null: every particle at the identity
    const uint8_t* group;
    ClockView now;
    Vec3<R> field;    // b0 direction
    bool alternating;
    R angularFrequency, phase;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        const R amplitude = alternating ? R(sin(double(angularFrequency) * now.time() + double(phase))) : R(1);
        const Vec3<R> b = amplitude * field;
        if (out.magneticField) accumulate(out.magneticField[i], b);
        if (!out.energy && !out.torque) return;
        const Vec3<R> mu = magnetic_moment(magnetization, dir, i);
        if (out.energy) out.energy[i] -= dot(mu, b);
        if (out.torque) accumulate(out.torque[i], bonded_geometry::cross(mu, b));
    }
};

template <class B, class R>
class MagneticFieldInteraction : public Interactor<B, R> {
public:
    MagneticFieldInteraction(const B& backend, InteractorScope scope, const Vec3<R>& field, bool alternating,
                             R angularFrequency, R phase)
        : Interactor<B, R>(std::move(scope)),
          backend_(backend),
          field_(field),
          alternating_(alternating),
          angularFrequency_(angularFrequency),
          phase_(phase) {}

    // No force: nothing to add to a Hessian or to pair forces.
    bool has_hessian() const override { return true; }
    void add_hessian(Particles<B, R>&, int, Tensor3<R>*) override {}
    bool has_pair_forces() const override { return true; }
    void add_pair_forces(Particles<B, R>&, int, Real4<R>*) override {}
    bool makes_magnetic_field() const override { return true; }

    void compute(Particles<B, R>& p, const ForceOutputs<R>& out) override {
        if (!out.energy && !out.torque && !out.magneticField) return;
        backend_.for_each(p.count, MagneticFieldTerm<R>{p.magnetization.data(), p.dir.empty() ? nullptr : p.dir.data(),
                                                        this->group(), p.now(), field_, alternating_,
                                                        angularFrequency_, phase_, out});
    }

private:
    const B& backend_;
    Vec3<R> field_;
    bool alternating_;
    R angularFrequency_, phase_;
};

// Alternating: the ACMagneticField variant (frequency and phase).
template <bool Alternating>
struct MagneticFieldComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);  // magnetic_field_read.cpp

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& external = static_cast<const ExternalSpec&>(s);
        const double b0 = external.values["b0"];
        const std::array<double, 3> d = external.values.vec3("direction");
        const double omega = Alternating ? 2.0 * 3.14159265358979323846 * external.values["frequency"] : 0.0;
        const double phase = Alternating ? external.values["phase"] : 0.0;
        return std::make_unique<MagneticFieldInteraction<B, R>>(
            build.backend, build.scope(external), Vec3<R>{R(b0 * d[0]), R(b0 * d[1]), R(b0 * d[2])}, Alternating,
            R(omega), R(phase));
    }
};

using ConstantMagneticField = MagneticFieldComponent<false>;
using ACMagneticField = MagneticFieldComponent<true>;

}  // namespace structmd
