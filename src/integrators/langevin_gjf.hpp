#pragma once
// ["Langevin","GJF"], Grønbech-Jensen-Farago. With b = 1/(1 + gamma dt/2), a = (1 - gamma dt/2) b and
// beta = sqrt(2 gamma m kT dt) xi, fresh each step:
//   x(n+1) = x + b dt v + b dt^2/(2m) F + b dt/(2m) beta
//   v(n+1) = a v + dt/(2m) (a F + F(n+1)) + (b/m) beta
// Configurational sampling is correct at any stable time step.
#include "integrators/integrator.hpp"
#include "integrators/langevin_inputs.hpp"
#include "integrators/thermal_noise.hpp"
#include "state/fault.hpp"

namespace structmd {

template <class R>
struct GjfDrift {
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
    DriftBookkeeping<R> bookkeeping;  // for every particle, moved or not (state/drift_bookkeeping.hpp)
    SMD_HD void operator()(int64_t i) const {
        if ((group && !group[i]) || held_fixed(vel[i])) {
            bookkeeping(i, pos[i]);
            return;
        }
        Real4<R> v = vel[i];
        const Real4<R> f = force[i];
        const R m = v.w;
        const R friction = frictionOf ? frictionOf[i] : gamma;
        const R b = R(1) / (R(1) + R(0.5) * friction * dt);
        const R a = (R(1) - R(0.5) * friction * dt) * b;
        const R amplitude = sqrt(R(2) * friction * m * kT * dt);
        const Vec3<R> xi = gaussian3<R>(noiseKey, NoisePurpose::integrator, i, now.step());
        const Vec3<R> beta{amplitude * xi.x, amplitude * xi.y, amplitude * xi.z};
        const R c = b * dt / (R(2) * m);
        const Vec3<R> move = (b * dt) * xyz(v) + c * (dt * xyz(f) + beta);
        fault.check_move(i, move);
        const Real4<R> p = displaced(pos[i], move, box, image[i]);
        pos[i] = p;
        bookkeeping(i, p);
        // The part of v(n+1) known before F(n+1); GjfKick adds dt/(2m) F(n+1).
        const R h = dt / (R(2) * m);
        v.x = a * v.x + h * a * f.x + (b / m) * beta.x;
        v.y = a * v.y + h * a * f.y + (b / m) * beta.y;
        v.z = a * v.z + h * a * f.z + (b / m) * beta.z;
        vel[i] = v;
    }
};

template <class R>
struct GjfKick {
    const Real4<R>* pos;
    Real4<R>* vel;
    const Real4<R>* force;
    const uint8_t* group;
    R dt;
    FaultSlot fault;
    SMD_HD void operator()(int64_t i) const {
        if ((group && !group[i]) || held_fixed(vel[i])) return;
        const Real4<R> f = force[i];
        const Real4<R> v = half_kick(vel[i], f, dt);
        vel[i] = v;
        fault.check(i, pos[i], v, f);
    }
};

template <class B, class R>
class LangevinGJF : public Integrator<B, R> {
public:
    LangevinGJF(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : Integrator<B, R>(scope),
          backend_(backend),
          friction_(v["frictionConstant"]),
          resetVelocities_(v["resetVelocities"] != 0.0) {}

    void begin(Particles<B, R>& p, ForceSource&) override {
        const IntegratorScope& s = this->scope();
        if (resetVelocities_)
            backend_.for_each(p.count, DrawThermalVelocities<R>{p.vel.data(), s.group, p.noise, p.now(), R(s.kT)});
    }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        const R dt = R(s.timeStep);
        forces.update_forces();
        const R* frictionOf = friction_ > 0.0 ? nullptr : p.friction.data();
        backend_.for_each(p.count, GjfDrift<R>{p.pos.data(), p.image.data(), p.vel.data(), p.force.data(), s.group,
                                               frictionOf, p.box, dt, R(friction_), R(s.kT), p.noise, p.now(), p.fault_slot(1),
                                               p.drift});
        forces.positions_moved(s.timeStep, true);
        forces.update_forces();
        backend_.for_each(p.count, GjfKick<R>{p.pos.data(), p.vel.data(), p.force.data(), s.group, dt, p.fault_slot()});
    }

private:
    const B& backend_;
    double friction_;
    bool resetVelocities_;
};

}  // namespace structmd
