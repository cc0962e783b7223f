#pragma once
// What both Langevin integrators (BBK, GJF) share: each particle's inputs to a step, and the
// integrator's friction, velocity reset and the kernel arguments built from them.
#include "integrators/integrator.hpp"
#include "integrators/langevin_inputs.hpp"
#include "integrators/thermal_noise.hpp"
#include "state/fault.hpp"

namespace structmd {

// A step's view of the particles. The bookkeeping is the engine's for the evaluation at the new
// positions (state/drift_bookkeeping.hpp): every particle gets it, moved or not.
template <class R>
struct LangevinParticles {
    Real4<R>* pos;
    Image* image;
    Real4<R>* vel;
    const Real4<R>* force;
    const uint8_t* group;
    const R* frictionOf;  // by particle; null: gamma for all
    Box<R> box;
    R dt, gamma, kT;
    NoiseKey noiseKey;
    ClockView now;
    FaultSlot fault;
    DriftBookkeeping<R> bookkeeping;

    // A particle outside the group or held fixed stays, with its bookkeeping done.
    SMD_HD bool stays(int64_t i) const {
        if (!(group && !group[i]) && !held_fixed(vel[i])) return false;
        bookkeeping(i, pos[i]);
        return true;
    }
    SMD_HD R friction(int64_t i) const { return frictionOf ? frictionOf[i] : gamma; }
    SMD_HD Vec3<R> noise(int64_t i) const { return gaussian3<R>(noiseKey, NoisePurpose::integrator, i, now.step()); }
};

template <class B, class R>
class LangevinIntegrator : public Integrator<B, R> {
public:
    LangevinIntegrator(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : Integrator<B, R>(scope),
          backend_(backend),
          friction_(v["frictionConstant"]),
          resetVelocities_(v["resetVelocities"] != 0.0) {}

    void begin(Particles<B, R>& p, ForceSource&) override {
        const IntegratorScope& s = this->scope();
        if (resetVelocities_)
            backend_.for_each(p.count, DrawThermalVelocities<R>{p.vel.data(), s.group, p.noise, p.now(), R(s.kT)});
    }

protected:
    // The step's kernel arguments; each particle's own friction (the state's frictionConstant
    // column) where the entry gives none.
    LangevinParticles<R> particles(Particles<B, R>& p) const {
        const IntegratorScope& s = this->scope();
        const R* frictionOf = friction_ > 0.0 ? nullptr : p.columns[StateColumn::frictionConstant].data();
        return {p.pos.data(), p.image.data(), p.vel.data(), p.force.data(), s.group,  frictionOf, p.box,
                R(s.timeStep), R(friction_),    R(s.kT),        p.noise,         p.now(), p.fault_slot(1), p.drift};
    }

    const B& backend_;

private:
    double friction_;
    bool resetVelocities_;
};

}  // namespace structmd
