#pragma once
// ["Magnetic","ForceCouplingMethod"]: magnetic particles that move and turn through a triply periodic
// Stokes fluid. Each step first turns the moments inside the particles as ["Magnetic","Fixed"] does,
// then moves and turns the particles by the force coupling method with rotation
// (hydrodynamics/fcm_rotation.hpp), by the forces and torques of the new moments:
//   x += dx,   q <- exp(dtheta / 2) q,
// dx and dtheta the translation and the lab-frame rotation vector of the fluid's step (deterministic
// and random). A moment is fixed in its body, so it turns with the particle.
#include <memory>
#include <string>

#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "core/quaternion.hpp"
#include "hydrodynamics/fcm_rotation.hpp"
#include "integrators/bdhi_grid.hpp"
#include "integrators/magnetic.hpp"

namespace structmd {

struct MagneticForceCouplingInputs : GridBdhiInputs {
    static std::vector<Parameter> parameters() {
        std::vector<Parameter> all = GridBdhiInputs::parameters();
        for (const Parameter& p : MagneticInputs::parameters()) all.push_back(p);
        return all;
    }
    static std::vector<TextOption> text_options() { return MagneticInputs::text_options(); }
    static constexpr bool rotates = true;
    static constexpr bool magnetic = true;
    static void validate(const ParameterValues& v, const std::string& path) {
        GridBdhiInputs::validate(v, path);
        MagneticInputs::validate(v, path);
    }
    static void validate_in_box(const ParameterValues& v, const std::array<double, 3>& box, const std::string& path) {
        require_periodic_box(box, path + ".type", "this integrator's fluid grid");
        make_fcm_rotation_plan(box.data(), v["hydrodynamicRadius"], v["tolerance"], path);
    }
};

// q <- exp(theta / 2) q for the group's particles, theta flat (3i, 3i+1, 3i+2).
template <class R>
struct RotateByVector {
    Real4<R>* dir;
    const R* rotation;
    const uint8_t* group;
    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        dir[i] = rotated(dir[i], Vec3<R>{rotation[3 * i], rotation[3 * i + 1], rotation[3 * i + 2]});
    }
};

template <class B, class R>
class MagneticForceCoupling : public GridBdhi<B, R> {
public:
    MagneticForceCoupling(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : GridBdhi<B, R>(backend, scope), moments_(backend, v), viscosity_(v["viscosity"]),
          radius_(v["hydrodynamicRadius"]), tolerance_(v["tolerance"]) {}

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        moments_.step(p, forces, s);
        prepare(p);
        forces.update_forces();
        mesh_->move(p, s.group, s.timeStep, s.kT, viscosity_, static_cast<uint64_t>(NoisePurpose::hydrodynamics) << 48,
                    displacement_.data(), rotation_.data());
        backend_.for_each(p.count, RotateByVector<R>{p.dir.data(), rotation_.data(), s.group});
        this->move_by(p, forces, displacement_.data());
    }

private:
    // The mesh for the present box, made once: a box that changes afterwards is refused.
    void prepare(const Particles<B, R>& p) override {
        const double box[3] = {double(p.box.length.x), double(p.box.length.y), double(p.box.length.z)};
        if (mesh_) {
            refuse_changed_box(this->scope(), box, mesh_->plan().translation.box, 3,
                               "[\"Magnetic\", \"ForceCouplingMethod\"]", "solves the Stokes flow");
        } else {
            mesh_ = std::make_unique<FcmRotationMesh<B, R>>(
                backend_, make_fcm_rotation_plan(box, radius_, tolerance_, this->scope().path));
        }
        backend_.resize(displacement_, static_cast<size_t>(3 * p.count));
        backend_.resize(rotation_, static_cast<size_t>(3 * p.count));
    }

    using GridBdhi<B, R>::backend_;
    MagnetizationDynamics<B, R> moments_;
    double viscosity_, radius_, tolerance_;
    std::unique_ptr<FcmRotationMesh<B, R>> mesh_;
    typename B::template Buffer<R> displacement_, rotation_;
};

}  // namespace structmd
