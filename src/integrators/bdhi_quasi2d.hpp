#pragma once
// ["BDHIDoublyPeriodic","Quasi2D"]: Brownian dynamics with hydrodynamic interactions of particles
// that move in a plane, periodic along x and y,
//   x += dt M F + dt kT div M + sqrt(2 kT dt) M^{1/2} W    (in x and y; z is not integrated),
// with the quasi-2D mobility (the plane in an unbounded 3D fluid) or the true 2D one
// (hydrodynamics/planar_mesh.hpp). As the force coupling method, only the integrator's group takes
// part: particles outside it neither push the fluid nor are carried by it.
#include <memory>
#include <string>

#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "hydrodynamics/planar_mesh.hpp"
#include "integrators/bdhi_grid.hpp"
#include "integrators/thermal_noise.hpp"

namespace structmd {

struct BdhiQuasi2DInputs : GridBdhiInputs {
    // Which fluid the plane is in (the order of PlanarHydrodynamics).
    static std::vector<TextOption> text_options() { return {{"hydrodynamicKernel", "Quasi2D", {"Quasi2D", "True2D"}, {}, ""}}; }
    static void validate_in_box(const ParameterValues& v, const std::array<double, 3>& box, const std::string& path) {
        require_periodic_box(box, path + ".type", "this integrator's fluid grid");
        make_planar_plan(box.data(), static_cast<PlanarHydrodynamics>(static_cast<int>(v["hydrodynamicKernel"])),
                         v["hydrodynamicRadius"], v["tolerance"], path);
    }
};

template <class B, class R>
class BdhiQuasi2D : public GridBdhi<B, R> {
public:
    BdhiQuasi2D(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : GridBdhi<B, R>(backend, scope), viscosity_(v["viscosity"]), radius_(v["hydrodynamicRadius"]),
          tolerance_(v["tolerance"]), kind_(static_cast<PlanarHydrodynamics>(static_cast<int>(v["hydrodynamicKernel"]))) {}

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        prepare(p);
        forces.update_forces();
        mesh_->displace(p, s.group, s.timeStep, viscosity_, s.kT, static_cast<uint64_t>(NoisePurpose::hydrodynamics) << 48,
                        displacement_.data());
        this->move_by(p, forces, displacement_.data());
    }

private:
    // The mesh for the present box, made once: a box whose x or y changes afterwards is refused.
    void prepare(const Particles<B, R>& p) override {
        const double box[2] = {double(p.box.length.x), double(p.box.length.y)};
        if (mesh_) {
            refuse_changed_box(this->scope(), box, mesh_->plan().box, 2, "[\"BDHIDoublyPeriodic\", \"Quasi2D\"]",
                               "solves the flow");
        } else {
            mesh_ = std::make_unique<PlanarMesh<B, R>>(backend_, make_planar_plan(box, kind_, radius_, tolerance_,
                                                                                  this->scope().path));
        }
        backend_.resize(displacement_, static_cast<size_t>(3 * p.count));
    }

    using GridBdhi<B, R>::backend_;
    double viscosity_, radius_, tolerance_;
    PlanarHydrodynamics kind_;
    std::unique_ptr<PlanarMesh<B, R>> mesh_;
    typename B::template Buffer<R> displacement_;  // flat, three numbers a particle
};

}  // namespace structmd
