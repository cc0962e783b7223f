#pragma once
// ["Brownian","EulerMaruyama"], overdamped dynamics without velocities: with the mobility
// M_i = 1 / (6 pi eta a_i) from each particle's radius,
//   x += dt M F + sqrt(2 kT M dt) xi.
#include "integrators/integrator.hpp"
#include "integrators/thermal_noise.hpp"
#include "state/fault.hpp"

namespace structmd {

struct BrownianInputs : IntegratorInputs {
    static std::vector<Parameter> parameters() {
        return {with_default(number("viscosity", "mass/(length time)", Must::be_positive), 0.0)};
    }
    static constexpr bool needsRadius = true;  // mobility 1 / (6 pi eta a)
    static constexpr bool overdamped = true;
    // Without a viscosity, each particle's mobility is D / (k_B T) from the state.
    static constexpr const char* fallbackParameter = "viscosity";
    static constexpr StateColumn fallbackColumn = StateColumn::translationalSelfDiffusion;
};

template <class R>
struct EulerMaruyamaStep {
    Real4<R>* pos;
    Image* image;
    const Real4<R>* force;
    const R* radius;
    const R* selfDiffusion;  // null: mobility from the viscosity and the radius
    const uint8_t* group;
    Box<R> box;
    R dt, viscosity, kT;
    NoiseKey noiseKey;
    ClockView now;
    FaultSlot fault;
    DriftBookkeeping<R> bookkeeping;  // for every particle, moved or not (state/drift_bookkeeping.hpp)
    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) {
            bookkeeping(i, pos[i]);
            return;
        }
        const Real4<R> f = force[i];
        const R mobility = selfDiffusion ? selfDiffusion[i] / kT
                                         : R(1) / (R(6 * 3.14159265358979323846) * viscosity * radius[i]);
        const R spread = sqrt(R(2) * kT * mobility * dt);
        const Vec3<R> xi = gaussian3<R>(noiseKey, NoisePurpose::integrator, i, now.step());
        const Vec3<R> move = (dt * mobility) * xyz(f) + spread * xi;
        fault.check_move(i, move);
        const Real4<R> p = displaced(pos[i], move, box, image[i]);
        pos[i] = p;
        fault.check(i, p, f);
        bookkeeping(i, p);
    }
};

template <class R>
struct StopParticles {
    Real4<R>* vel;
    const uint8_t* group;
    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        vel[i].x = vel[i].y = vel[i].z = R(0);
    }
};

template <class B, class R>
class BrownianEulerMaruyama : public Integrator<B, R> {
public:
    BrownianEulerMaruyama(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : Integrator<B, R>(scope), backend_(backend), viscosity_(v["viscosity"]) {}

    bool overdamped() const override { return true; }

    // Overdamped particles have no velocity of their own: the kinetic energy reads 0.
    void begin(Particles<B, R>& p, ForceSource&) override {
        backend_.for_each(p.count, StopParticles<R>{p.vel.data(), this->scope().group});
    }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        forces.update_forces();
        const R* selfDiffusion = viscosity_ > 0.0 ? nullptr : p.columns[StateColumn::translationalSelfDiffusion].data();
        backend_.for_each(p.count, EulerMaruyamaStep<R>{p.pos.data(), p.image.data(), p.force.data(), p.radius.data(),
                                                        selfDiffusion, s.group, p.box, R(s.timeStep), R(viscosity_), R(s.kT),
                                                        p.noise, p.now(), p.fault_slot(1), p.drift});
        forces.positions_moved(s.timeStep, true);
    }

private:
    const B& backend_;
    double viscosity_;
};

}  // namespace structmd
