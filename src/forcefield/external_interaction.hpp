#pragma once
// A field acting on each particle alone (external_potential.hpp), generic in its potential. It
// adds force and energy; an external field has no pair partner and contributes no virial.
#include <cstdint>
#include <string>

#include "forcefield/external_potential.hpp"
#include "forcefield/interactor.hpp"

namespace structmd {

template <class Potential, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct ExternalKernel {
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    const R* radius;
    const uint8_t* group;
    Params params;
    ClockView now;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        Vec3<R> f{0, 0, 0};
        const R e = Potential::compute(xyz(pos[i]), radius[i], params, R(now.time()), f);
        add_to_outputs<WantForce, WantEnergy, false>(out, i, f, e, zero_tensor<R>());
    }
};

template <class B, class R, class Potential>
class ExternalInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<R>;

    ExternalInteraction(const B& backend, InteractorScope scope, const Params& params)
        : Interactor<B, R>(std::move(scope)), backend_(backend), params_(params) {}

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        ForceOutputs<R> own = out;
        own.virial = nullptr;
        dispatch_outputs(own, [&](auto force, auto energy, auto) {
            backend_.for_each(particles.count,
                              ExternalKernel<Potential, R, decltype(force)::value, decltype(energy)::value, false>{
                                  particles.pos.data(), particles.radius.data(), this->group(), params_,
                                  particles.now(), own});
        });
    }

private:
    const B& backend_;
    Params params_;
};

}  // namespace structmd
