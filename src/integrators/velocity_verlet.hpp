#pragma once
// ["Verlet","VelocityVerlet"], NVE: v += dt/2 F/m; x += dt v; F = F(x); v += dt/2 F/m.
#include "integrators/integrator.hpp"

namespace structmd {

struct VelocityVerletInputs : IntegratorInputs {
    static constexpr bool underDomains = true;
};

// Also does the engine's bookkeeping for the evaluation at the new positions, for every particle,
// moved or not. ["DPD","Verlet"] and ["SPH","Verlet"] (pair_verlet.hpp) kick with their pair forces too.
template <class R>
struct VerletKickDrift {
    const uint8_t* group;
    Real4<R>* pos;
    Image* image;
    Real4<R>* vel;
    Real4<R>* force;
    Box<R> box;
    R dt;
    FaultSlot fault;
    DriftBookkeeping<R> bookkeeping;
    const Real4<R>* extraForce = nullptr;  // added to force (kick_force); null: none
    SMD_HD void operator()(int64_t i) const {
        Real4<R> p = pos[i];
        if (!(group && !group[i]) && !held_fixed(vel[i])) {
            const Real4<R> v = half_kick(vel[i], kick_force(force, extraForce, i), dt);
            vel[i] = v;
            const Vec3<R> move = dt * xyz(v);
            fault.check_move(i, move);
            p = displaced(p, move, box, image[i]);
            pos[i] = p;
        }
        bookkeeping(i, p);
    }
};

template <class B, class R>
class VelocityVerlet : public Integrator<B, R> {
public:
    VelocityVerlet(const B& backend, const IntegratorScope& scope, const ParameterValues&)
        : Integrator<B, R>(scope), backend_(backend) {}

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const R dt = R(this->time_step());
        forces.update_forces();
        backend_.for_each(p.count, VerletKickDrift<R>{this->scope().group, p.pos.data(), p.image.data(), p.vel.data(),
                                                      p.force.data(), p.box, dt, p.fault_slot(1), p.drift});
        forces.positions_moved(this->time_step(), true);
        forces.update_forces();
        backend_.for_each(p.count, ClosingHalfKick<R>{this->scope().group, p.vel.data(), p.force.data(), dt, p.fault_slot()});
    }

private:
    const B& backend_;
};

}  // namespace structmd
