#pragma once
// ["Langevin","GJF"], Grønbech-Jensen-Farago. With b = 1/(1 + gamma dt/2), a = (1 - gamma dt/2) b and
// beta = sqrt(2 gamma m kT dt) xi, fresh each step:
//   x(n+1) = x + b dt v + b dt^2/(2m) F + b dt/(2m) beta
//   v(n+1) = a v + dt/(2m) (a F + F(n+1)) + (b/m) beta
// Configurational sampling is correct at any stable time step.
#include "integrators/langevin_step.hpp"

namespace structmd {

template <class R>
struct GjfDrift {
    LangevinParticles<R> in;
    SMD_HD void operator()(int64_t i) const {
        if (in.stays(i)) return;
        Real4<R> v = in.vel[i];
        const Real4<R> f = in.force[i];
        const R m = v.w;
        const R dt = in.dt;
        const R friction = in.friction(i);
        const R b = R(1) / (R(1) + R(0.5) * friction * dt);
        const R a = (R(1) - R(0.5) * friction * dt) * b;
        const R amplitude = sqrt(R(2) * friction * m * in.kT * dt);
        const Vec3<R> xi = in.noise(i);
        const Vec3<R> beta{amplitude * xi.x, amplitude * xi.y, amplitude * xi.z};
        const R c = b * dt / (R(2) * m);
        const Vec3<R> move = (b * dt) * xyz(v) + c * (dt * xyz(f) + beta);
        in.fault.check_move(i, move);
        const Real4<R> p = displaced(in.pos[i], move, in.box, in.image[i]);
        in.pos[i] = p;
        in.bookkeeping(i, p);
        // The part of v(n+1) known before F(n+1); ClosingHalfKick adds dt/(2m) F(n+1).
        const R h = dt / (R(2) * m);
        v.x = a * v.x + h * a * f.x + (b / m) * beta.x;
        v.y = a * v.y + h * a * f.y + (b / m) * beta.y;
        v.z = a * v.z + h * a * f.z + (b / m) * beta.z;
        in.vel[i] = v;
    }
};

template <class B, class R>
class LangevinGJF : public LangevinIntegrator<B, R> {
public:
    using LangevinIntegrator<B, R>::LangevinIntegrator;

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        forces.update_forces();
        this->backend_.for_each(p.count, GjfDrift<R>{this->particles(p)});
        forces.positions_moved(s.timeStep, true);
        forces.update_forces();
        this->backend_.for_each(p.count, ClosingHalfKick<R>{s.group, p.vel.data(), p.force.data(), R(s.timeStep),
                                                            p.fault_slot()});
    }
};

}  // namespace structmd
