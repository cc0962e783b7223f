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
    // The last step's closing half kick, left to this pass (steps joined, integrator.hpp): the same
    // two half kicks with the same force, in one pass over the particles instead of two. Its check
    // reports at the step whose state it makes, this one, as ClosingHalfKick would have.
    bool closesLastStep = false;
    FaultSlot lastStepFault{};
    SMD_HD void operator()(int64_t i) const {
        Real4<R> p = pos[i];
        if (!(group && !group[i]) && !held_fixed(vel[i])) {
            const Real4<R> f = kick_force(force, extraForce, i);
            Real4<R> v = vel[i];
            if (closesLastStep) {
                v = half_kick(v, f, dt);
                lastStepFault.check_kick(i, v, f);
            }
            v = half_kick(v, f, dt);
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

    // Between two steps nothing changes the forces: the closing half kick of one and the opening
    // half kick of the next read the same ones, so joined steps kick twice in one pass.
    bool joins_steps() const override { return true; }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const R dt = R(this->time_step());
        const typename Integrator<B, R>::StepJoin join = this->step_join();
        forces.update_forces();
        VerletKickDrift<R> kickDrift{this->scope().group, p.pos.data(), p.image.data(), p.vel.data(),
                                     p.force.data(), p.box, dt, p.fault_slot(1), p.drift};
        kickDrift.closesLastStep = join.fromLast;
        kickDrift.lastStepFault = p.fault_slot();
        backend_.for_each(p.count, kickDrift);
        forces.positions_moved(this->time_step(), true);
        forces.update_forces();
        if (!join.toNext)
            backend_.for_each(p.count, ClosingHalfKick<R>{this->scope().group, p.vel.data(), p.force.data(), dt, p.fault_slot()});
    }

private:
    const B& backend_;
};

}  // namespace structmd
