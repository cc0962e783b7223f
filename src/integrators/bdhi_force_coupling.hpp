#pragma once
// ["BDHITriplyPeriodic","ForceCouplingMethod"]: Brownian dynamics with hydrodynamic interactions in
// a triply periodic box of Stokes flow,
//   x += dt M F + sqrt(2 kT dt) M^{1/2} W,
// with the force coupling method's mobility M (hydrodynamics/fcm_mesh.hpp). As in UAMMD, only the
// integrator's group takes part: particles outside it neither push the fluid nor are carried by it.
#include <memory>
#include <string>

#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "hydrodynamics/fcm_mesh.hpp"
#include "integrators/bdhi_grid.hpp"

namespace structmd {

struct BdhiForceCouplingInputs : GridBdhiInputs {
    static void validate_in_box(const ParameterValues& v, const std::array<double, 3>& box, const std::string& path) {
        require_periodic_box(box, path + ".type", "this integrator's fluid grid");
        make_fcm_plan(box.data(), v["hydrodynamicRadius"], v["tolerance"], path);
    }
};

template <class B, class R>
class BdhiForceCoupling : public GridBdhi<B, R> {
public:
    BdhiForceCoupling(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : GridBdhi<B, R>(backend, scope), viscosity_(v["viscosity"]), radius_(v["hydrodynamicRadius"]),
          tolerance_(v["tolerance"]) {}

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        prepare(p);
        forces.update_forces();
        mesh_->displace(p, s.group, s.timeStep, s.kT, FcmGreen<R>{R(1.0 / viscosity_)},
                        static_cast<uint64_t>(NoisePurpose::hydrodynamics) << 48, displacement_.data());
        this->move_by(p, forces, displacement_.data());
    }

private:
    // The mesh for the present box, made once: a box that changes afterwards is refused.
    void prepare(const Particles<B, R>& p) override {
        const double box[3] = {double(p.box.length.x), double(p.box.length.y), double(p.box.length.z)};
        if (mesh_) {
            refuse_changed_box(this->scope(), box, mesh_->plan().box, 3,
                               "[\"BDHITriplyPeriodic\", \"ForceCouplingMethod\"]", "solves the Stokes flow");
        } else {
            mesh_ = std::make_unique<FcmMesh<B, R, FcmGreen<R>>>(backend_, make_fcm_plan(box, radius_, tolerance_, this->scope().path));
        }
        backend_.resize(displacement_, static_cast<size_t>(3 * p.count));
    }

    using GridBdhi<B, R>::backend_;
    double viscosity_, radius_, tolerance_;
    std::unique_ptr<FcmMesh<B, R, FcmGreen<R>>> mesh_;
    typename B::template Buffer<R> displacement_;
};

}  // namespace structmd
