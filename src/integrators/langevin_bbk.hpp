#pragma once
// ["Langevin","BBK"], Brünger-Brooks-Karplus leapfrog. With g = gamma dt / 2 and the random force
// R = sqrt(2 m gamma kT / dt) xi:
//   v(n+1/2) = [(1 - g) v(n-1/2) + dt (F_n + R) / m] / (1 + g);   x(n+1) = x(n) + dt v(n+1/2).
// Velocities are the half-step ones. begin() turns full-step velocities v(0) into v(-1/2) with half a
// kick back, so positions move once per step from the start. With stopTransRotSteps = N > 0 the
// group's global translation and rotation are removed when the stage begins and after every step
// that reaches a multiple of N (global_motion.hpp), as UAMMD-structured does for a solute that must
// not drift or spin.
#include "integrators/global_motion.hpp"
#include "integrators/langevin_step.hpp"

namespace structmd {

struct LangevinBBKInputs : LangevinInputs {
    static constexpr bool underDomains = true;  // its noise is keyed by the particle's global id
    static constexpr const char* wholeSystemParameter = "stopTransRotSteps";
    static constexpr const char* wholeSystemEffect = "removing the whole system's motion";
    static std::vector<Parameter> parameters() {
        std::vector<Parameter> all = LangevinInputs::parameters();
        all.push_back(with_default(number("stopTransRotSteps", "step", Must::be_integer), 0.0));
        return all;
    }
    static void validate(const ParameterValues& v, const std::string& path) {
        if (v["stopTransRotSteps"] < 0.0)
            throw input_error(path + ".parameters.stopTransRotSteps", "expected a number of steps >= 0 (0: never)");
    }
};

template <class R>
struct HalfKickBack {
    Real4<R>* vel;
    const Real4<R>* force;
    const uint8_t* group;
    R dt;
    SMD_HD void operator()(int64_t i) const {
        if ((group && !group[i]) || held_fixed(vel[i])) return;
        vel[i] = half_kick(vel[i], force[i], -dt);
    }
};

template <class R>
struct BbkStep {
    LangevinParticles<R> in;
    SMD_HD void operator()(int64_t i) const {
        if (in.stays(i)) return;
        Real4<R> v = in.vel[i];
        const Real4<R> f = in.force[i];
        const R m = v.w;
        const R dt = in.dt;
        const R friction = in.friction(i);
        const R g = R(0.5) * friction * dt;
        const R noise = sqrt(R(2) * m * friction * in.kT / dt);
        const Vec3<R> xi = in.noise(i);
        v.x = ((R(1) - g) * v.x + dt * (f.x + noise * xi.x) / m) / (R(1) + g);
        v.y = ((R(1) - g) * v.y + dt * (f.y + noise * xi.y) / m) / (R(1) + g);
        v.z = ((R(1) - g) * v.z + dt * (f.z + noise * xi.z) / m) / (R(1) + g);
        in.vel[i] = v;
        const Vec3<R> move = dt * xyz(v);
        in.fault.check_move(i, move);
        const Real4<R> p = displaced(in.pos[i], move, in.box, in.image[i]);
        in.pos[i] = p;
        in.fault.check(i, p, v, f);
        in.bookkeeping(i, p);
    }
};

template <class B, class R>
class LangevinBBK : public LangevinIntegrator<B, R> {
public:
    LangevinBBK(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : LangevinIntegrator<B, R>(backend, scope, v),
          stopTransRotSteps_(static_cast<int64_t>(v["stopTransRotSteps"])) {}

    void begin(Particles<B, R>& p, ForceSource& forces) override {
        LangevinIntegrator<B, R>::begin(p, forces);
        const IntegratorScope& s = this->scope();
        if (stopTransRotSteps_ > 0) remove_rigid_motion(this->backend_, p, s.group, R(0));  // full-step v(0) at x(0)
        forces.update_forces();
        this->backend_.for_each(p.count, HalfKickBack<R>{p.vel.data(), p.force.data(), s.group, R(s.timeStep)});
    }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        forces.update_forces();
        this->backend_.for_each(p.count, BbkStep<R>{this->particles(p)});
        // A reduction, so the host waits: only on the steps that ask for it. It moves the
        // particles again, so the engine does its bookkeeping itself then.
        const bool removal = stopTransRotSteps_ > 0 && (p.timeline.step() + 1) % stopTransRotSteps_ == 0;
        if (removal) remove_rigid_motion(this->backend_, p, s.group, R(s.timeStep));
        forces.positions_moved(s.timeStep, !removal);
    }

private:
    int64_t stopTransRotSteps_;  // 0: never
};

}  // namespace structmd
