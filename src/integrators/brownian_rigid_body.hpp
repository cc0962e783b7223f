#pragma once
// ["Brownian","EulerMaruyamaRigidBody"], overdamped dynamics of spheres with orientations: the
// translation of ["Brownian","EulerMaruyama"] and, with the rotational mobility
// M_r = 1 / (8 pi eta a^3) from each particle's radius, a lab-frame rotation
//   theta = dt M_r T + sqrt(2 kT M_r dt) xi_r,    q <- exp(theta / 2) q
// of each orientation q by its torque T. Without a viscosity both mobilities are D / (k_B T) from the
// state's translationalSelfDiffusion and rotationalSelfDiffusion columns.
#include "core/quaternion.hpp"
#include "integrators/brownian.hpp"

namespace structmd {

struct BrownianRigidBodyInputs : BrownianInputs {
    static constexpr bool rotates = true;
};

template <class R>
struct RotateByTorque {
    Real4<R>* dir;
    const Real4<R>* torque;
    const R* radius;
    const R* rotationalDiffusion;  // null: mobility from the viscosity and the radius
    const uint8_t* group;
    R dt, viscosity, kT;
    NoiseKey noiseKey;
    ClockView now;
    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        const R a = radius[i];
        const R mobility = rotationalDiffusion ? rotationalDiffusion[i] / kT
                                               : R(1) / (R(8 * 3.14159265358979323846) * viscosity * a * a * a);
        const R spread = sqrt(R(2) * kT * mobility * dt);
        const Vec3<R> xi = gaussian3<R>(noiseKey, NoisePurpose::rotation, i, now.step());
        const Vec3<R> theta = (dt * mobility) * xyz(torque[i]) + spread * xi;
        dir[i] = rotated(dir[i], theta);
    }
};

template <class B, class R>
class BrownianEulerMaruyamaRigidBody : public BrownianEulerMaruyama<B, R> {
public:
    BrownianEulerMaruyamaRigidBody(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : BrownianEulerMaruyama<B, R>(backend, scope, v), backend_(backend), viscosity_(v["viscosity"]) {}

    // The torques are those of the positions and orientations the step starts from, made in the same
    // pass as the forces; the rotation reads them before the translation moves on.
    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        forces.update_forces();
        const R* rotationalDiffusion = viscosity_ > 0.0 ? nullptr : p.columns[StateColumn::rotationalSelfDiffusion].data();
        backend_.for_each(p.count, RotateByTorque<R>{p.dir.data(), p.torque.data(), p.radius.data(), rotationalDiffusion,
                                                     s.group, R(s.timeStep), R(viscosity_), R(s.kT), p.noise, p.now()});
        BrownianEulerMaruyama<B, R>::step(p, forces);
    }

private:
    const B& backend_;
    double viscosity_;
};

}  // namespace structmd
