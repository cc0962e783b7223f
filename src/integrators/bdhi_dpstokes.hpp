#pragma once
// ["BDHIDoublyPeriodic","DPStokes"]: Brownian dynamics with hydrodynamic interactions in a fluid
// periodic along x and y, between no-slip walls at z = -H/2 ("bottom") or z = -H/2 and H/2 ("slit"),
// or open along z ("none"), Euler-Maruyama:
//   x += dt M F + dt kT div M + sqrt(2 kT dt) M^{1/2} W,
// M the slab's mobility (hydrodynamics/slab_mesh.hpp), M^{1/2} W by the Lanczos iteration on the
// product M v (hydrodynamics/lanczos_sqrt.hpp), and div M, which is not zero near a wall, by UAMMD's
// random finite difference: with W' ~ N(0, I) independent of W and a small delta,
//   div M ~ (M(x + delta W'/2) W' - M(x - delta W'/2) W') / delta,
// exact in the mean up to O(delta^2). delta = a sqrt(eps) (eps the precision's), which balances the
// rounding of the difference against its truncation. Only the integrator's group takes part;
// rotations are not coupled (w_d, beta_d and alpha_d, UAMMD's torque kernel, are read and unused).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "core/precise.hpp"
#include "hydrodynamics/fcm_mesh.hpp"
#include "hydrodynamics/lanczos_sqrt.hpp"
#include "hydrodynamics/slab_mesh.hpp"
#include "integrators/bdhi_grid.hpp"
#include "integrators/bdhi_kernels.hpp"
#include "integrators/thermal_noise.hpp"

namespace structmd {

struct BdhiDPStokesInputs : IntegratorInputs {
    static constexpr bool oneFluid = true;
    static constexpr bool overdamped = true;
    static std::vector<Parameter> parameters() {
        return {number("viscosity", "mass/(length time)", Must::be_positive),
                number("hydrodynamicRadius", "length", Must::be_positive),
                number("nx", "1", Must::be_positive_integer),
                number("ny", "1", Must::be_positive_integer),
                with_default(number("nz", "1", Must::be_non_negative), 0.0),
                number("Lx", "length", Must::be_positive),
                number("Ly", "length", Must::be_positive),
                number("H", "length", Must::be_positive),
                number("w", "1", Must::be_positive),
                with_default(number("beta", "1"), -1.0),
                with_default(number("alpha", "1"), -1.0),
                with_default(number("w_d", "1", Must::be_non_negative), 0.0),
                with_default(number("beta_d", "1"), -1.0),
                with_default(number("alpha_d", "1"), -1.0),
                with_default(number("tolerance", "1", Must::be_positive), 1e-7)};
    }
    static std::vector<TextOption> text_options() { return {{"mode", "none", {"none", "bottom", "slit"}, {}, ""}}; }

    static void validate(const ParameterValues& v, const std::string& path) {
        const std::string at = path + ".parameters.";
        // UAMMD's kernel exp(beta (sqrt(1 - (r / (alpha h))^2) - 1)) is not real beyond alpha h.
        if (v["alpha"] > 0.5 * v["w"])
            throw input_error(at + "alpha", "must be at most w/2 = " + std::to_string(0.5 * v["w"]) + ", got " +
                                                std::to_string(v["alpha"]));
        if (v["w_d"] > 0.0 && v["alpha_d"] > 0.5 * v["w_d"])
            throw input_error(at + "alpha_d", "must be at most w_d/2 = " + std::to_string(0.5 * v["w_d"]) + ", got " +
                                                  std::to_string(v["alpha_d"]));
        if (!(v["tolerance"] <= 0.1))
            throw input_error(at + "tolerance", "expected a Lanczos tolerance <= 0.1, got " + std::to_string(v["tolerance"]));
        const double nz = v["nz"];
        if (nz != 0.0 && !(nz >= 3.0 && nz == std::floor(nz)))
            throw input_error(at + "nz", "expected an integer >= 3 (or leave it out), got " + std::to_string(nz));
        // Before any count becomes an int: nx = 2^31 wrapped to a negative grid and was blamed on
        // the radius.
        const double points[3] = {v["nx"], v["ny"], nz_wanted(v)};
        const char* names[3] = {"nx", "ny", "nz"};
        for (int d = 0; d < 3; ++d)
            if (!(points[d] <= kMaxGridPoints))
                throw input_error(at + names[d], "expected at most 2^30 grid points, got " + precise(points[d]));
        if (!(points[0] * points[1] * points[2] <= kMaxGridPoints))
            throw input_error(at + names[std::max_element(points, points + 3) - points],
                              "the grid would need " + precise(points[0]) + " x " + precise(points[1]) + " x " +
                                  precise(points[2]) + " points, more than 2^30");
        const SlabPlan plan = slab_plan(v);
        // A coarser grid than 2 sigma does not resolve the Gaussian (sigma = a / sqrt(pi)).
        const double spacings[3] = {v["Lx"] / v["nx"], v["Ly"] / v["ny"], v["H"] / (plan.grid.nz - 1)};
        for (int d = 0; d < 3; ++d)
            if (spacings[d] > 2.0 * plan.sigma)
                throw input_error(at + names[d], "the grid spacing " + std::to_string(spacings[d]) +
                                                     " is wider than twice the Gaussian's width a/sqrt(pi) = " +
                                                     std::to_string(plan.sigma) + ": refine the grid");
        if (plan.support >= plan.grid.nx || plan.support >= plan.grid.ny)
            throw input_error(at + "hydrodynamicRadius", "the Gaussian spans " + std::to_string(plan.support) +
                                                             " grid points, more than the grid has along x or y: "
                                                             "the box is too small for this radius");
        if (plan.walls != SlabWalls::none && plan.height < 2.0 * v["hydrodynamicRadius"])
            throw input_error(at + "H", "the slab must be at least one diameter high");
    }

    // The slab in the input's box, at the load and at every parameter change.
    static void validate_in_box(const ParameterValues& v, const std::array<double, 3>& box, const std::string& path) {
        require_periodic_box(box, path + ".type", "this integrator's fluid grid");
        check_fits_box(v["Lx"], v["Ly"], v["H"], box.data(), path);
    }

    // Lx and Ly are the box's x and y; the slab fits in its z.
    static void check_fits_box(double lx, double ly, double height, const double box[3], const std::string& path) {
        const double lengths[2] = {lx, ly};
        for (int d = 0; d < 2; ++d)
            if (!(std::fabs(box[d] - lengths[d]) <= 1e-6 * lengths[d]))
                throw input_error(path + ".parameters.L" + std::string(1, "xy"[d]),
                                  "is " + std::to_string(lengths[d]) + " but the box's " + std::string(1, "xy"[d]) +
                                      " length is " + std::to_string(box[d]) + " (the box may not change either)");
        if (!(box[2] >= height))
            throw input_error(path + ".parameters.H", "the slab of height " + std::to_string(height) +
                                                          " does not fit in the box's z length " + std::to_string(box[2]));
    }

    // The z nodes: nz where given, else as many as make the z spacing the finer of x's and y's.
    static double nz_wanted(const ParameterValues& v) {
        return v["nz"] > 0.0 ? v["nz"] : std::ceil(v["H"] / std::min(v["Lx"] / v["nx"], v["Ly"] / v["ny"])) + 1.0;
    }

    static SlabPlan slab_plan(const ParameterValues& v) {
        const int sizes[3] = {static_cast<int>(v["nx"]), static_cast<int>(v["ny"]), static_cast<int>(nz_wanted(v))};
        const double box[2] = {v["Lx"], v["Ly"]};
        return make_slab_plan(sizes, box, v["H"], v["hydrodynamicRadius"], static_cast<SlabWalls>(static_cast<int>(v["mode"])),
                              v["tolerance"]);
    }
};

// shifted = pos + c W'
template <class R>
struct ShiftPositions {
    const Real4<R>* pos;
    const R* w;
    R c;
    Real4<R>* shifted;
    SMD_HD void operator()(int64_t i) const {
        Real4<R> r = pos[i];
        r.x += c * w[3 * i];
        r.y += c * w[3 * i + 1];
        r.z += c * w[3 * i + 2];
        shifted[i] = r;
    }
};

// 1 for a group particle on a wall of the slab or beyond it, else 0.
template <class R>
struct OnSlabWall {
    const Real4<R>* pos;
    const uint8_t* group;
    R bottom, top;
    bool slit;
    SMD_HD double operator()(int64_t i) const {
        if (group && !group[i]) return 0.0;
        const R z = pos[i].z;
        return z <= bottom || (slit && z >= top) ? 1.0 : 0.0;
    }
};

// drift += c (plus - minus)
template <class R>
struct AddFiniteDifference {
    const R* plus;
    const R* minus;
    R c;
    R* drift;
    SMD_HD void operator()(int64_t i) const { drift[i] += c * (plus[i] - minus[i]); }
};

template <class B, class R>
class BdhiDPStokes : public GridBdhi<B, R> {
public:
    // More iterations than this mean a tolerance below what the precision can give.
    static constexpr int kMaxIterations = 100;

    BdhiDPStokes(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : GridBdhi<B, R>(backend, scope), plan_(BdhiDPStokesInputs::slab_plan(v)),
          viscosity_(v["viscosity"]), radius_(v["hydrodynamicRadius"]),
          // Below 100 eps the iteration cannot see its own convergence.
          lanczos_(backend, std::max(v["tolerance"], 100.0 * std::numeric_limits<R>::epsilon()), kMaxIterations,
                   "the mobility of " + scope.name) {}

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        const int64_t n = p.count;
        prepare(p);
        forces.update_forces();
        backend_.for_each(n, FlattenForces<R>{p.force.data(), flatForce_.data()});
        mesh_->place(n, p.pos.data(), s.group);
        mesh_->apply(flatForce_.data(), drift_.data(), viscosity_);
        const bool thermal = s.kT > 0.0;
        if (thermal) {
            backend_.for_each(n, DrawHydrodynamicNoise<R>{s.group, p.noise, p.now(), gaussian_.data()});
            refuse_particles_on_a_wall(p);
            lanczos_.apply_sqrt(3 * n, gaussian_.data(), noise_.data(),
                                [&](const R* v, R* out) { mesh_->apply(v, out, viscosity_); });
            thermal_drift(p, s.kT);
        }
        backend_.for_each(n, BdhiMove<R>{p.pos.data(), p.image.data(), p.force.data(), drift_.data(),
                                         thermal ? noise_.data() : nullptr, nullptr, s.group, p.box, R(s.timeStep),
                                         R(std::sqrt(2.0 * s.kT * s.timeStep)), p.fault_slot(1), p.drift});
        forces.positions_moved(s.timeStep, true);
    }

private:
    // A particle on a wall (or beyond it) spreads nothing, so M has a zero row: the Lanczos square
    // root then either fails ("not positive definite", alone) or moves it off the wall by its
    // truncation error (among others). Refused, naming the lowest such id and the step; the count
    // is one reduction, the positions are read only when there is one.
    void refuse_particles_on_a_wall(const Particles<B, R>& p) {
        if (plan_.walls == SlabWalls::none) return;
        const R bottom = R(-0.5 * plan_.height), top = R(0.5 * plan_.height);
        const bool slit = plan_.walls == SlabWalls::slit;
        const uint8_t* group = this->scope().group;
        if (backend_.reduce(p.count, OnSlabWall<R>{p.pos.data(), group, bottom, top, slit}, 0.0) == 0.0) return;
        std::vector<Real4<R>> positions(static_cast<size_t>(p.count));
        backend_.download(p.pos, positions.data(), positions.size());
        const OnSlabWall<R> onWall{positions.data(), nullptr, bottom, top, slit};
        for (int64_t i = 0; i < p.count; ++i)
            if (onWall(i) > 0.0)
                throw Error(STRUCTMD_ERR_NUMERICAL,
                            "step " + std::to_string(p.timeline.step() + 1) + ", particle id " + std::to_string(i) +
                                ": it lies on the wall at z = " + precise(positions[i].z <= bottom ? bottom : top) +
                                " (z = " + precise(positions[i].z) + "), where the slab's mobility vanishes and " +
                                "its noise cannot be drawn; keep the particles inside the slab (a wall potential)");
    }

    // drift_ += kT div M by the random finite difference.
    void thermal_drift(Particles<B, R>& p, double kT) {
        const IntegratorScope& s = this->scope();
        const int64_t n = p.count;
        const double delta = radius_ * std::sqrt(double(std::numeric_limits<R>::epsilon()));
        backend_.for_each(n, DrawHydrodynamicNoise<R>{s.group, p.noise, p.now(), rfdNoise_.data(),
                                                            NoisePurpose::randomFiniteDifference});
        backend_.for_each(n, ShiftPositions<R>{p.pos.data(), rfdNoise_.data(), R(0.5 * delta), shifted_.data()});
        mesh_->place(n, shifted_.data(), s.group);
        mesh_->apply(rfdNoise_.data(), plus_.data(), viscosity_);
        backend_.for_each(n, ShiftPositions<R>{p.pos.data(), rfdNoise_.data(), R(-0.5 * delta), shifted_.data()});
        mesh_->place(n, shifted_.data(), s.group);
        mesh_->apply(rfdNoise_.data(), minus_.data(), viscosity_);
        backend_.for_each(3 * n, AddFiniteDifference<R>{plus_.data(), minus_.data(), R(kT / delta), drift_.data()});
    }

    // The mesh, made once for the box it starts with: Lx and Ly must be the box's x and y, which
    // may not change afterwards.
    void prepare(const Particles<B, R>& p) override {
        const IntegratorScope& s = this->scope();
        const double box[3] = {double(p.box.length.x), double(p.box.length.y), double(p.box.length.z)};
        BdhiDPStokesInputs::check_fits_box(plan_.box[0], plan_.box[1], plan_.height, box, s.path);
        if (!mesh_) mesh_ = std::make_unique<SlabMesh<B, R>>(backend_, plan_);
        const size_t flat = static_cast<size_t>(3 * p.count);
        for (auto* buffer : {&flatForce_, &drift_, &gaussian_, &noise_, &rfdNoise_, &plus_, &minus_})
            backend_.resize(*buffer, s.kT > 0.0 || buffer == &flatForce_ || buffer == &drift_ ? flat : 0);
        backend_.resize(shifted_, s.kT > 0.0 ? static_cast<size_t>(p.count) : 0);
    }

    using GridBdhi<B, R>::backend_;
    SlabPlan plan_;
    double viscosity_, radius_;
    LanczosSqrt<B, R> lanczos_;
    std::unique_ptr<SlabMesh<B, R>> mesh_;
    typename B::template Buffer<R> flatForce_, drift_, gaussian_, noise_, rfdNoise_, plus_, minus_;  // flat
    typename B::template Buffer<Real4<R>> shifted_;
};

}  // namespace structmd
