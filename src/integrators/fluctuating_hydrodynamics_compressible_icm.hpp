#pragma once
// ["FluctuatingHydrodynamics","CompressibleInertialCoupling"]: the inertial coupling method for
// neutrally buoyant particles in a compressible fluctuating fluid (Balboa Usabiaga, Pagonabarraga &
// Delgado-Buscalioni, J. Comput. Phys. 235, 701 (2013)), as UAMMD's Hydro::ICM_Compressible, in a
// triply periodic box. The fluid (hydrodynamics/compressible_fluid.hpp) takes an explicit
// three-stage Runge-Kutta step with the force density S F spread from the particles held over it;
// the particles move with the fluid around them, u = J v:
//   q^{n+1/2} = q^n + dt/2 J^n v^n
//   (rho, g)^{n+1} from (rho, g)^n with f = S^{n+1/2} F^{n+1/2}
//   q^{n+1}   = q^n + dt/2 J^{n+1/2} (v^n + v^{n+1}),
// F^{n+1/2} the force field's at q^{n+1/2}, J and S Peskin's three-point kernel on the staggered grid
// (hydrodynamics/staggered_fluid.hpp). The particles' velocities are set to J^{n+1} v^{n+1}. Particles
// outside the group neither push the fluid nor move.
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "hydrodynamics/compressible_fluid.hpp"
#include "hydrodynamics/fcm_mesh.hpp"
#include "hydrodynamics/gaussian_spreading.hpp"
#include "hydrodynamics/staggered_fluid.hpp"
#include "integrators/fluctuating_hydrodynamics_icm.hpp"
#include "integrators/integrator.hpp"
#include "integrators/thermal_noise.hpp"
#include "neighbour/line_bins.hpp"

namespace structmd {

// The cells along each axis: cellDimX/Y/Z where any is given (> 0), else n = floor(0.91 L / a) from
// the hydrodynamic radius a (the three-point kernel's a = 0.91 h); at least 4 either way.
inline std::array<int, 3> compressible_icm_cells(const ParameterValues& v, const std::array<double, 3>& box,
                                                 const std::string& path) {
    std::array<int, 3> cells{};
    const char* names[3] = {"cellDimX", "cellDimY", "cellDimZ"};
    const bool given = v["cellDimX"] > 0 || v["cellDimY"] > 0 || v["cellDimZ"] > 0;
    const double radius = v["hydrodynamicRadius"];
    if (!given && !(radius > 0))
        throw input_error(path + ".parameters.hydrodynamicRadius",
                          "give a hydrodynamicRadius > 0 or the cells, cellDimX, cellDimY and cellDimZ");
    for (int d = 0; d < 3; ++d) {
        if (given) {
            if (!(v[names[d]] >= 4))
                throw input_error(path + ".parameters." + names[d],
                                  "cellDimX, cellDimY and cellDimZ go together, each at least 4 cells");
            cells[d] = static_cast<int>(v[names[d]]);
        } else {
            const double wanted = std::floor(box[d] * kPeskin3RadiusOverSpacing / radius);
            if (!(wanted <= 1024.0))
                throw input_error(path + ".parameters.hydrodynamicRadius",
                                  "the fluid grid would need more than 1024 cells along " + std::string(1, "xyz"[d]));
            cells[d] = std::max(4, static_cast<int>(wanted));
        }
    }
    if (double(cells[0]) * cells[1] * cells[2] > kMaxGridPoints)
        throw input_error(path + ".parameters", "the fluid grid would have more than 2^30 cells");
    return cells;
}

struct CompressibleIcmInputs : IntegratorInputs {
    static constexpr bool oneFluid = true;
    static std::vector<Parameter> parameters() {
        return {number("shearViscosity", "mass/(length time)", Must::be_positive),
                number("bulkViscosity", "mass/(length time)", Must::be_non_negative),
                number("speedOfSound", "length/time", Must::be_positive),
                number("density", "mass/length^3", Must::be_positive),
                with_default(number("hydrodynamicRadius", "length"), 0),
                with_default(number("cellDimX", "1", Must::be_integer), 0),
                with_default(number("cellDimY", "1", Must::be_integer), 0),
                with_default(number("cellDimZ", "1", Must::be_integer), 0)};
    }
    // UAMMD-structured's one initial condition: uniform density, fluid at rest.
    static std::vector<TextOption> text_options() { return {{"initialCondition", "none", {"none"}, {}, ""}}; }
    static void validate_in_box(const ParameterValues& v, const std::array<double, 3>& box, const std::string& path) {
        require_periodic_box(box, path + ".type", "the compressible inertial coupling method's fluid");
        compressible_icm_cells(v, box, path);
    }
};

template <class B, class R>
class CompressibleInertialCoupling : public Integrator<B, R> {
public:
    CompressibleInertialCoupling(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : Integrator<B, R>(scope), backend_(backend), values_(v) {
        properties_.shearViscosity = v["shearViscosity"];
        properties_.bulkViscosity = v["bulkViscosity"];
        properties_.speedOfSound = v["speedOfSound"];
        properties_.density = v["density"];
    }

    void begin(Particles<B, R>& p, ForceSource&) override {
        prepare(p);
        interpolate(p, fluid_->velocity(), start_.data());
        backend_.for_each(p.count, IcmSetVelocities<R>{p.vel.data(), start_.data(), this->scope().group});
    }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        prepare(p);
        const R dt = R(s.timeStep);

        // q^{n+1/2} = q^n + dt/2 J^n v^n.
        interpolate(p, fluid_->velocity(), start_.data());
        backend_.for_each(p.count, IcmHalfMove<R>{p.pos.data(), p.image.data(), p.force.data(), start_.data(), s.group,
                                                  p.box, R(0.5) * dt, p.fault_slot(1), p.drift});
        forces.positions_moved(0.5 * s.timeStep, true);
        forces.update_forces();
        interpolate(p, fluid_->velocity(), midOld_.data());

        // The fluid's step with the force density S F at q^{n+1/2}.
        fluid_->clear_forcing();
        bins_->sort(p.count, StaggeredParticleLine<R>{p.pos.data(), s.group, fluid_->grid()});
        backend_.for_each(int64_t(fluid_->grid().cells.ny) * fluid_->grid().cells.nz,
                          InertialFluidSpreadLine<R, Real4Vectors<R>>{p.pos.data(), Real4Vectors<R>{p.force.data()},
                                                                      bins_->order(), bins_->line_start(), fluid_->grid(),
                                                                      R(1.0 / fluid_->cell_volume()), fluid_->forcing()});
        fluid_->step(s.timeStep, s.kT, p.noise.seed, static_cast<uint64_t>(NoisePurpose::hydrodynamics) << 48, p.now());

        // q^{n+1} = q^n + dt/2 J^{n+1/2} (v^n + v^{n+1}), from q^{n+1/2}.
        interpolate(p, fluid_->velocity(), midNew_.data());
        backend_.for_each(p.count, IcmFinalMove<R>{p.pos.data(), p.image.data(), p.force.data(), start_.data(),
                                                   midOld_.data(), midNew_.data(), s.group, p.box, R(0.5) * dt,
                                                   p.fault_slot(), p.drift});
        forces.positions_moved(s.timeStep, true);
        interpolate(p, fluid_->velocity(), start_.data());
        backend_.for_each(p.count, IcmSetVelocities<R>{p.vel.data(), start_.data(), s.group});
    }

    // The fluid's density, momentum and velocity, so that a run continued from a checkpoint is the
    // run that went on (the Runge-Kutta step keeps nothing else from one step to the next).
    std::vector<double> state() const override { return fluid_ ? fluid_->save() : std::vector<double>{}; }
    // A state saved before the fluid existed (or for another grid) starts it at rest again.
    void restore(const std::vector<double>& saved) override {
        if (!fluid_) {
            restored_ = saved;
        } else if (!fluid_->load(saved)) {
            fluid_->start_at_rest();
        }
    }

private:
    // The grid for the box the integrator starts with (a box that changes afterwards is refused),
    // the fluid at rest with the uniform density (UAMMD-structured's initialCondition "none").
    void prepare(const Particles<B, R>& p) {
        const IntegratorScope& s = this->scope();
        const std::array<double, 3> box = {double(p.box.length.x), double(p.box.length.y), double(p.box.length.z)};
        if (fluid_) {
            refuse_changed_box(s, box.data(), box_.data(), 3,
                               "[\"FluctuatingHydrodynamics\", \"CompressibleInertialCoupling\"]", "keeps the fluid");
        } else {
            require_periodic_box(box, s.path + ".type", "the compressible inertial coupling method's fluid");
            box_ = box;
            const std::array<int, 3> n = compressible_icm_cells(values_, box, s.path);
            StaggeredGrid<R> grid{};
            grid.cells = FftGrid{n[0], n[1], n[2]};
            grid.length = p.box.length;
            grid.spacing = Vec3<R>{R(box[0] / n[0]), R(box[1] / n[1]), R(box[2] / n[2])};
            fluid_ = std::make_unique<CompressibleFluid<B, R>>(backend_, grid, properties_);
            bins_ = std::make_unique<LineBins<B>>(backend_, n[1] * n[2]);
            if (s.log) log_grid(n, box);
            if (!restored_.empty()) fluid_->load(restored_);
            restored_.clear();
        }
        backend_.resize(start_, static_cast<size_t>(3 * p.count));
        backend_.resize(midOld_, static_cast<size_t>(3 * p.count));
        backend_.resize(midNew_, static_cast<size_t>(3 * p.count));
    }

    // The grid, the radius it gives and the stability numbers of the explicit step: the acoustic
    // c dt / h and the viscous (4 eta / 3 + zeta) dt / (rho h^2).
    void log_grid(const std::array<int, 3>& n, const std::array<double, 3>& box) const {
        const IntegratorScope& s = this->scope();
        const double h = std::min({box[0] / n[0], box[1] / n[1], box[2] / n[2]});
        const double acoustic = properties_.speedOfSound * s.timeStep / h;
        const double viscous = (4.0 * properties_.shearViscosity / 3.0 + properties_.bulkViscosity) * s.timeStep /
                               (properties_.density * h * h);
        s.log->info(s.name + ": compressible fluid of " + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
                    std::to_string(n[2]) + " cells, hydrodynamic radius " +
                    std::to_string(kPeskin3RadiusOverSpacing * box[0] / n[0]) + ", acoustic CFL number " +
                    std::to_string(acoustic) + ", viscous " + std::to_string(viscous));
    }

    void interpolate(const Particles<B, R>& p, const R* field, R* out) {
        backend_.for_each(p.count, InertialFluidInterpolate<R>{p.pos.data(), this->scope().group, fluid_->grid(), field, out});
    }

    const B& backend_;
    ParameterValues values_;
    typename CompressibleFluid<B, R>::Properties properties_;
    std::array<double, 3> box_{};
    std::unique_ptr<CompressibleFluid<B, R>> fluid_;
    std::unique_ptr<LineBins<B>> bins_;
    std::vector<double> restored_;
    typename B::template Buffer<R> start_, midOld_, midNew_;
};

}  // namespace structmd
