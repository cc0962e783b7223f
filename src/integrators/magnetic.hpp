#pragma once
// The magnetic integrators: the moments' own (Neel) dynamics by the stochastic Landau-Lifshitz-Gilbert
// equation, in each particle's body frame,
//   dm/dt = -gamma / (1 + alpha^2) [m x b + alpha m x (m x b)],   |m| = 1,
// with b the field at the particle (External fields, dipoles), the anisotropy field
// 2 K / M_s (m . e_z) e_z along the body's easy axis z, and a thermal field of variance
// 2 alpha kT / (gamma M dt) per component (M the moment's magnitude), which makes
// exp(M m . B / kT) the stationary distribution. "LLG_Heun" integrates it in Stratonovich's sense
// (predictor, field again, corrector), "LLG_Euler" by one Euler step, "none" leaves the moments fixed
// in their bodies.
//   ["Magnetic","Fixed"]: particles that do not move; only the moments turn.
//   ["Magnetic","Brownian"]: the moments turn first, then the particles move as in
//   ["Brownian","EulerMaruyamaRigidBody"] with the torques of the new moments, which turn a rigid
//   dipole (Brownian relaxation) with its body.
#include <string>

#include "core/error.hpp"
#include "forcefield/bonded_geometry.hpp"
#include "forcefield/magnetic_moment.hpp"
#include "integrators/brownian_rigid_body.hpp"
#include "integrators/integrator.hpp"
#include "integrators/thermal_noise.hpp"

namespace structmd {

enum class MagneticAlgorithm { none = 0, eulerLLG = 1, heunLLG = 2 };  // the order of the text option

struct MagneticInputs : IntegratorInputs {
    static std::vector<Parameter> parameters() {
        return {number("msat", "moment/volume", Must::be_positive),
                with_default(number("damping", "1"), -1.0), with_default(number("gyroRatio", "1/(field time)"), -1.0)};
    }
    static std::vector<TextOption> text_options() {
        return {{"magneticIntegrationAlgorithm", nullptr, {"none", "LLG_Euler", "LLG_Heun"}, {}, ""}};
    }
    static constexpr bool magnetic = true;
    static void validate(const ParameterValues& v, const std::string& path) {
        if (static_cast<MagneticAlgorithm>(v["magneticIntegrationAlgorithm"]) == MagneticAlgorithm::none) return;
        for (const char* name : {"damping", "gyroRatio"})
            if (!(v[name] > 0.0))
                throw input_error(path + ".parameters." + name,
                                  std::string("the Landau-Lifshitz-Gilbert algorithms need ") + name + " > 0");
    }
};

struct MagneticFixedInputs : MagneticInputs {
    static constexpr bool overdamped = true;  // nothing moves: no kinetic energy
};

struct MagneticBrownianInputs : MagneticInputs {
    static std::vector<Parameter> parameters() {
        std::vector<Parameter> all = BrownianRigidBodyInputs::parameters();
        for (const Parameter& p : MagneticInputs::parameters()) all.push_back(p);
        return all;
    }
    static constexpr bool needsRadius = BrownianRigidBodyInputs::needsRadius;
    static constexpr bool overdamped = BrownianRigidBodyInputs::overdamped;
    static constexpr bool rotates = BrownianRigidBodyInputs::rotates;
    static constexpr const char* fallbackParameter = BrownianRigidBodyInputs::fallbackParameter;
    static constexpr StateColumn fallbackColumn = BrownianRigidBodyInputs::fallbackColumn;
};

// dm/dt of the Landau-Lifshitz-Gilbert equation for the unit moment m in the field b.
template <class R>
SMD_HD SMD_INLINE Vec3<R> llg_rate(const Vec3<R>& m, const Vec3<R>& b, R damping, R gyroRatio) {
    const Vec3<R> mxb = bonded_geometry::cross(m, b);
    return (-gyroRatio / (R(1) + damping * damping)) * (mxb + damping * bonded_geometry::cross(m, mxb));
}

// One stage of a step of the moments. Euler: m + dt dm/dt, normalised. Heun's predictor keeps the
// moment it started from in `start` and leaves the predicted one unnormalised (the field is
// evaluated with it, as a Heun stage); the corrector averages the two slopes and normalises.
enum class LlgStage { euler, predictor, corrector };

template <class R>
struct LlgStep {
    Real4<R>* magnetization;
    Real4<R>* start;  // Heun: the moments at the start of the step
    const Real4<R>* field;
    const Real4<R>* dir;      // null: every particle at the identity
    const R* anisotropy;      // null: K = 0
    const uint8_t* group;
    R dt, kT, damping, gyroRatio, msat;
    NoiseKey noiseKey;
    ClockView now;
    LlgStage stage;

    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        const Real4<R> mm = magnetization[i];
        if (!(mm.w > R(0))) return;
        const Vec3<R> m = xyz(mm);
        Vec3<R> b = to_body_frame(dir, i, xyz(field[i]));
        // The same Wiener increment in both Heun stages: the noise is drawn by (particle, step).
        if (kT > R(0)) {
            const R spread = sqrt(R(2) * kT * damping / (gyroRatio * mm.w * dt));
            b += spread * gaussian3<R>(noiseKey, NoisePurpose::magnetization, i, now.step());
        }
        if (anisotropy) b.z += R(2) * anisotropy[i] / msat * m.z;
        const Vec3<R> dm = dt * llg_rate(m, b, damping, gyroRatio);
        Vec3<R> next = m + dm;
        if (stage == LlgStage::predictor) {
            start[i] = mm;
        } else {
            if (stage == LlgStage::corrector) next = R(0.5) * (xyz(start[i]) + next);
            const R norm = sqrt(dot(next, next));
            next = (R(1) / norm) * next;
        }
        magnetization[i] = Real4<R>{next.x, next.y, next.z, mm.w};
    }
};

// The moments' part of a step, at fixed positions and orientations.
template <class B, class R>
class MagnetizationDynamics {
public:
    MagnetizationDynamics(const B& backend, const ParameterValues& v)
        : backend_(backend),
          algorithm_(static_cast<MagneticAlgorithm>(v["magneticIntegrationAlgorithm"])),
          damping_(v["damping"]),
          gyroRatio_(v["gyroRatio"]),
          msat_(v["msat"]) {}

    void step(Particles<B, R>& p, ForceSource& forces, const IntegratorScope& s) {
        if (algorithm_ == MagneticAlgorithm::none) return;
        if (algorithm_ == MagneticAlgorithm::eulerLLG) {
            stage(p, forces, s, LlgStage::euler);
        } else {
            backend_.resize(start_, p.count);
            stage(p, forces, s, LlgStage::predictor);
            stage(p, forces, s, LlgStage::corrector);
        }
    }

private:
    void stage(Particles<B, R>& p, ForceSource& forces, const IntegratorScope& s, LlgStage which) {
        forces.update_magnetic_field();
        const auto& anisotropy = p.columns[StateColumn::anisotropy];
        backend_.for_each(p.count, LlgStep<R>{p.magnetization.data(), start_.data(), p.magneticField.data(),
                                              p.dir.empty() ? nullptr : p.dir.data(),
                                              anisotropy.empty() ? nullptr : anisotropy.data(), s.group,
                                              R(s.timeStep), R(s.kT), R(damping_), R(gyroRatio_), R(msat_), p.noise,
                                              p.now(), which});
        forces.magnetization_changed();
    }

    const B& backend_;
    MagneticAlgorithm algorithm_;
    double damping_, gyroRatio_, msat_;
    typename B::template Buffer<Real4<R>> start_;
};

template <class B, class R>
class MagneticFixed : public Integrator<B, R> {
public:
    MagneticFixed(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : Integrator<B, R>(scope), backend_(backend), moments_(backend, v) {}

    bool overdamped() const override { return true; }
    void begin(Particles<B, R>& p, ForceSource&) override {
        backend_.for_each(p.count, StopParticles<R>{p.vel.data(), this->scope().group});
    }
    void step(Particles<B, R>& p, ForceSource& forces) override {
        moments_.step(p, forces, this->scope());
        // Nothing moved, but time-dependent fields are read at the next step's time.
        forces.magnetization_changed();
    }

private:
    const B& backend_;
    MagnetizationDynamics<B, R> moments_;
};

template <class B, class R>
class MagneticBrownian : public BrownianEulerMaruyamaRigidBody<B, R> {
public:
    MagneticBrownian(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : BrownianEulerMaruyamaRigidBody<B, R>(backend, scope, v), moments_(backend, v) {}

    void step(Particles<B, R>& p, ForceSource& forces) override {
        moments_.step(p, forces, this->scope());
        BrownianEulerMaruyamaRigidBody<B, R>::step(p, forces);
    }

private:
    MagnetizationDynamics<B, R> moments_;
};

}  // namespace structmd
