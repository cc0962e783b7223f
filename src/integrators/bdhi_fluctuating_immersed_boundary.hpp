#pragma once
// ["BDHITriplyPeriodic","FluctuatingImmersedBoundary"]: Brownian dynamics with hydrodynamic
// interactions in a triply periodic box by the fluctuating immersed boundary method (Delong, Balboa
// Usabiaga, Delgado-Buscalioni, Griffith & Donev, J. Chem. Phys. 140, 134110 (2014)): the fluid's
// velocity v on a staggered grid from the particles' forces, a random stress and a random finite
// difference (hydrodynamics/immersed_boundary_mesh.hpp), and the particles moved by the simple
// midpoint scheme of that paper (the one UAMMD's BDHI::FIB runs),
//   q^{n+1/2} = q^n + dt/2 J(q^n) v,   q^{n+1} = q^n + dt J(q^{n+1/2}) v,
// one Stokes solve per step with the forces at q^n. Evaluating J at the midpoint gives the
// kT (dJ/dq) : L^{-1} S part of the thermal drift kT div M, the random finite difference in v the
// kT J L^{-1} (div S) part, so that the step samples the Boltzmann distribution without div M ever
// being computed. As in UAMMD, only the integrator's group takes part: particles outside it neither
// push the fluid nor are carried by it.
#include <memory>
#include <string>

#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "hydrodynamics/immersed_boundary_mesh.hpp"
#include "integrators/bdhi_grid.hpp"
#include "integrators/bdhi_kernels.hpp"
#include "integrators/thermal_noise.hpp"

namespace structmd {

struct BdhiFluctuatingImmersedBoundaryInputs : IntegratorInputs {
    static constexpr bool oneFluid = true;
    static constexpr bool overdamped = true;
    // UAMMD-structured's: the radius defaults to 1; the tolerance is read but the Peskin kernel has
    // a fixed support, so nothing depends on it.
    static std::vector<Parameter> parameters() {
        return {number("viscosity", "mass/(length time)", Must::be_positive),
                with_default(number("hydrodynamicRadius", "length", Must::be_positive), 1.0),
                with_default(number("tolerance", "1", Must::be_positive), 1e-3)};
    }
    static void validate_in_box(const ParameterValues& v, const std::array<double, 3>& box, const std::string& path) {
        require_periodic_box(box, path + ".type", "this integrator's fluid grid");
        make_immersed_boundary_plan(box.data(), v["hydrodynamicRadius"], path);
    }
};

template <class B, class R>
class BdhiFluctuatingImmersedBoundary : public GridBdhi<B, R> {
public:
    // The random finite difference's step over the grid spacing: small enough for its truncation
    // error, large enough that the difference of two spreads keeps digits in this precision.
    static constexpr double kRfdStepOverSpacing = sizeof(R) >= 8 ? 1e-6 : 1e-4;

    BdhiFluctuatingImmersedBoundary(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : GridBdhi<B, R>(backend, scope), viscosity_(v["viscosity"]), radius_(v["hydrodynamicRadius"]) {}

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        const int64_t n = p.count;
        prepare(p);
        forces.update_forces();
        const bool thermal = s.kT > 0.0;
        if (thermal)
            backend_.for_each(n, DrawHydrodynamicNoise<R>{s.group, p.noise, p.now(), rfdNoise_.data(),
                                                          NoisePurpose::randomFiniteDifference});
        const ImmersedBoundaryPlan& plan = mesh_->plan();
        mesh_->solve(p, s.group, s.timeStep, viscosity_, s.kT, thermal ? rfdNoise_.data() : nullptr,
                     kRfdStepOverSpacing * plan.spacing[0], static_cast<uint64_t>(NoisePurpose::hydrodynamics) << 48);
        mesh_->interpolate(n, p.pos.data(), s.group, 1.0, velocity_.data());
        backend_.for_each(n, MidpointPositions<R>{p.pos.data(), velocity_.data(), R(0.5 * s.timeStep), midpoint_.data()});
        mesh_->interpolate(n, midpoint_.data(), s.group, s.timeStep, displacement_.data());
        this->move_by(p, forces, displacement_.data());
    }

private:
    // The mesh for the present box, made once: a box that changes afterwards is refused.
    void prepare(const Particles<B, R>& p) override {
        const double box[3] = {double(p.box.length.x), double(p.box.length.y), double(p.box.length.z)};
        if (mesh_) {
            refuse_changed_box(this->scope(), box, mesh_->plan().box, 3,
                               "[\"BDHITriplyPeriodic\", \"FluctuatingImmersedBoundary\"]", "solves the Stokes flow");
        } else {
            const ImmersedBoundaryPlan plan = make_immersed_boundary_plan(box, radius_, this->scope().path);
            mesh_ = std::make_unique<ImmersedBoundaryMesh<B, R>>(backend_, plan);
            if (this->scope().log)
                this->scope().log->info(this->scope().name + ": fluctuating immersed boundary grid " +
                                        std::to_string(plan.grid.nx) + " x " + std::to_string(plan.grid.ny) + " x " +
                                        std::to_string(plan.grid.nz) + ", hydrodynamic radius " +
                                        std::to_string(plan.radius) + " (asked for " + std::to_string(radius_) + ")");
        }
        const size_t flat = static_cast<size_t>(3 * p.count);
        for (auto* buffer : {&velocity_, &displacement_}) backend_.resize(*buffer, flat);
        backend_.resize(midpoint_, static_cast<size_t>(p.count));
        if (this->scope().kT > 0.0) backend_.resize(rfdNoise_, flat);
    }

    using GridBdhi<B, R>::backend_;
    double viscosity_, radius_;
    std::unique_ptr<ImmersedBoundaryMesh<B, R>> mesh_;
    typename B::template Buffer<R> velocity_, displacement_, rfdNoise_;
    typename B::template Buffer<Real4<R>> midpoint_;
};

}  // namespace structmd
