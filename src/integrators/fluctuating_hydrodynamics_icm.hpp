#pragma once
// ["FluctuatingHydrodynamics","IncompressibleInertialCoupling"]: the inertial coupling method (Balboa
// Usabiaga, Delgado-Buscalioni, Griffith & Donev, Comput. Methods Appl. Mech. Eng. 269, 139 (2014))
// for neutrally buoyant particles (excess mass 0, as UAMMD's Hydro::ICM) in an incompressible
// fluctuating fluid in a triply periodic box. The fluid (hydrodynamics/staggered_fluid.hpp) obeys
//   rho dv/dt = -grad p + eta L v + D(sqrt(2 eta kT) W) - D(rho v v^T) + S F,   D v = 0,
// and each particle moves with the fluid around it, u = J v. One step (the paper's eq. 36-40):
//   q^{n+1/2} = q^n + dt/2 J^n v^n
//   v^{n+1}   = P (rho/dt - eta/2 L)^{-1} [(rho/dt + eta/2 L) v^n + D W^n - D(rho v v^T)^{n+1/2}
//                                          + S^{n+1/2} F^{n+1/2} (+ the thermal drift)]
//   q^{n+1}   = q^n + dt/2 J^{n+1/2} (v^n + v^{n+1}),
// the advection by Adams-Bashforth, F^{n+1/2} the force field's at q^{n+1/2}. The particles'
// velocities are set to J^{n+1} v^{n+1}. Particles outside the group neither push the fluid nor move.
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "hydrodynamics/fcm_mesh.hpp"
#include "hydrodynamics/gaussian_spreading.hpp"
#include "hydrodynamics/staggered_fluid.hpp"
#include "integrators/integrator.hpp"
#include "integrators/thermal_noise.hpp"
#include "neighbour/line_bins.hpp"

namespace structmd {


// The cells along each axis: cellDimX/Y/Z where given, else as UAMMD chooses them from the radius,
// n = floor(L / (a / 0.91)) rounded up to an FFT-friendly size; at least 4 either way.
inline std::array<int, 3> icm_cells(const ParameterValues& v, const std::array<double, 3>& box, const std::string& path) {
    std::array<int, 3> cells{};
    const char* names[3] = {"cellDimX", "cellDimY", "cellDimZ"};
    const bool given = v["cellDimX"] > 0 || v["cellDimY"] > 0 || v["cellDimZ"] > 0;
    for (int d = 0; d < 3; ++d) {
        if (given) {
            if (!(v[names[d]] >= 4))
                throw input_error(path + ".parameters." + names[d],
                                  "cellDimX, cellDimY and cellDimZ go together, each at least 4 cells");
            cells[d] = static_cast<int>(v[names[d]]);
        } else {
            const double wanted = std::floor(box[d] * kPeskin3RadiusOverSpacing / v["hydrodynamicRadius"]);
            if (!(wanted <= 1024.0))
                throw input_error(path + ".parameters.hydrodynamicRadius",
                                  "the fluid grid would need more than 1024 cells along " + std::string(1, "xyz"[d]));
            cells[d] = fft_friendly_size(std::max(4, static_cast<int>(wanted)));
        }
    }
    if (double(cells[0]) * cells[1] * cells[2] > kMaxGridPoints)
        throw input_error(path + ".parameters", "the fluid grid would have more than 2^30 cells");
    return cells;
}

struct IcmInputs : IntegratorInputs {
    static constexpr bool oneFluid = true;
    static std::vector<Parameter> parameters() {
        return {number("viscosity", "mass/(length time)", Must::be_positive),
                number("density", "mass/length^3", Must::be_positive),
                number("hydrodynamicRadius", "length", Must::be_positive),
                with_default(number("cellDimX", "1", Must::be_non_negative), 0),
                with_default(number("cellDimY", "1", Must::be_non_negative), 0),
                with_default(number("cellDimZ", "1", Must::be_non_negative), 0),
                with_default(boolean("sumThermalDrift"), 0),
                with_default(boolean("removeTotalMomentum"), 1)};
    }
    static void validate(const ParameterValues& v, const std::string& path) {
        for (const char* name : {"cellDimX", "cellDimY", "cellDimZ"})
            if (v[name] != std::floor(v[name]))
                throw input_error(path + ".parameters." + name, "expected a whole number of cells");
    }
    static void validate_in_box(const ParameterValues& v, const std::array<double, 3>& box, const std::string& path) {
        require_periodic_box(box, path + ".type", "the inertial coupling method's fluid");
        icm_cells(v, box, path);
    }
};

// The predictor: the velocity J^n v^n is stored (flat) and the particle moves by dt/2 of it.
template <class R>
struct IcmHalfMove {
    Real4<R>* pos;
    Image* image;
    const Real4<R>* force;
    const R* velocity;  // J^n v^n, flat
    const uint8_t* group;
    Box<R> box;
    R halfDt;
    FaultSlot fault;
    DriftBookkeeping<R> bookkeeping;
    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) {
            bookkeeping(i, pos[i]);
            return;
        }
        const Vec3<R> move = halfDt * Vec3<R>{velocity[3 * i], velocity[3 * i + 1], velocity[3 * i + 2]};
        fault.check_move(i, move);
        const Real4<R> p = displaced(pos[i], move, box, image[i]);
        pos[i] = p;
        bookkeeping(i, p);
    }
};

// The corrector from q^{n+1/2}: q^{n+1} = q^{n+1/2} + dt/2 (J^{n+1/2} v^n + J^{n+1/2} v^{n+1} - J^n v^n).
template <class R>
struct IcmFinalMove {
    Real4<R>* pos;
    Image* image;
    const Real4<R>* force;
    const R* start;      // J^n v^n
    const R* midOld;     // J^{n+1/2} v^n
    const R* midNew;     // J^{n+1/2} v^{n+1}
    const uint8_t* group;
    Box<R> box;
    R halfDt;
    FaultSlot fault;
    DriftBookkeeping<R> bookkeeping;
    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) {
            bookkeeping(i, pos[i]);
            return;
        }
        Vec3<R> move;
        move.x = halfDt * (midOld[3 * i] + midNew[3 * i] - start[3 * i]);
        move.y = halfDt * (midOld[3 * i + 1] + midNew[3 * i + 1] - start[3 * i + 1]);
        move.z = halfDt * (midOld[3 * i + 2] + midNew[3 * i + 2] - start[3 * i + 2]);
        fault.check_move(i, move);
        const Real4<R> p = displaced(pos[i], move, box, image[i]);
        pos[i] = p;
        fault.check(i, p, force[i]);
        bookkeeping(i, p);
    }
};

// The particles' velocities (group members): u = J v, the mass in w kept.
template <class R>
struct IcmSetVelocities {
    Real4<R>* vel;
    const R* velocity;
    const uint8_t* group;
    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        vel[i].x = velocity[3 * i];
        vel[i].y = velocity[3 * i + 1];
        vel[i].z = velocity[3 * i + 2];
    }
};

// The random finite difference of the thermal drift (Delong et al., J. Chem. Phys. 140, 134110
// (2014)): the positions q +- delta/2 W' and the vectors +-W' they spread, W' ~ N(0, I) per particle.
template <class R>
struct IcmDriftProbe {
    const Real4<R>* pos;
    const uint8_t* group;
    NoiseKey noise;
    ClockView now;
    R halfDelta, sign;
    Box<R> box;
    Real4<R>* probe;
    R* vectors;
    SMD_HD void operator()(int64_t i) const {
        Vec3<R> w{R(0), R(0), R(0)};
        if (!group || group[i]) w = gaussian3<R>(noise, NoisePurpose::randomFiniteDifference, i, now.step());
        Image ignored{};
        probe[i] = displaced(pos[i], (sign * halfDelta) * w, box, ignored);
        vectors[3 * i] = sign * w.x;
        vectors[3 * i + 1] = sign * w.y;
        vectors[3 * i + 2] = sign * w.z;
    }
};

// field *= scale (the initial fluid's amplitude).
template <class R>
struct IcmScaleField {
    R* field;
    R scale;
    SMD_HD void operator()(int64_t i) const { field[i] *= scale; }
};

template <class B, class R>
class IncompressibleInertialCoupling : public Integrator<B, R> {
public:
    IncompressibleInertialCoupling(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : Integrator<B, R>(scope), backend_(backend), values_(v), viscosity_(v["viscosity"]), density_(v["density"]),
          sumThermalDrift_(v["sumThermalDrift"] != 0), removeTotalMomentum_(v["removeTotalMomentum"] != 0) {}

    void begin(Particles<B, R>& p, ForceSource&) override {
        prepare(p);
        interpolate(p, p.pos.data(), vel_.data(), start_.data());
        backend_.for_each(p.count, IcmSetVelocities<R>{p.vel.data(), start_.data(), this->scope().group});
    }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        prepare(p);
        const R dt = R(s.timeStep);
        const int64_t points = grid_.cells.points();
        const double cellVolume = double(grid_.spacing.x) * grid_.spacing.y * grid_.spacing.z;

        // q^{n+1/2} = q^n + dt/2 J^n v^n.
        interpolate(p, p.pos.data(), vel_.data(), start_.data());
        backend_.for_each(p.count, IcmHalfMove<R>{p.pos.data(), p.image.data(), p.force.data(), start_.data(), s.group,
                                                  p.box, R(0.5) * dt, p.fault_slot(1), p.drift});
        forces.positions_moved(0.5 * s.timeStep, true);
        forces.update_forces();
        interpolate(p, p.pos.data(), vel_.data(), midOld_.data());

        // The explicit part of the fluid's step, then S F dt / rho (and the thermal drift) added to it.
        const bool noisy = s.kT > 0.0;
        if (noisy)
            backend_.for_each(points, DrawStaggeredNormals<R>{stress_.data(), points, 6, p.noise.seed,
                                                              static_cast<uint64_t>(NoisePurpose::hydrodynamics) << 48, p.now()});
        backend_.for_each(points, StaggeredFluidForcing<R>{vel_.data(), noisy ? stress_.data() : nullptr, advection_.data(),
                                                           rhs_.data(), grid_, R(0.5 * s.timeStep * viscosity_ / density_),
                                                           R(std::sqrt(2.0 * s.kT * viscosity_ * s.timeStep / cellVolume) / density_),
                                                           R(s.timeStep / density_), R(density_), firstStep_});
        firstStep_ = false;
        spread(p, p.pos.data(), Real4Vectors<R>{p.force.data()}, R(s.timeStep / (density_ * cellVolume)));
        if (sumThermalDrift_ && noisy) add_thermal_drift(p, cellVolume);

        // v^{n+1}: the Crank-Nicolson solve and the projection in Fourier space.
        solve(R(0.5 * s.timeStep * viscosity_ / density_));

        // q^{n+1} = q^n + dt/2 J^{n+1/2} (v^n + v^{n+1}), from q^{n+1/2}.
        interpolate(p, p.pos.data(), vel_.data(), midNew_.data());
        backend_.for_each(p.count, IcmFinalMove<R>{p.pos.data(), p.image.data(), p.force.data(), start_.data(),
                                                   midOld_.data(), midNew_.data(), s.group, p.box, R(0.5) * dt,
                                                   p.fault_slot(), p.drift});
        forces.positions_moved(s.timeStep, true);
        interpolate(p, p.pos.data(), vel_.data(), start_.data());
        backend_.for_each(p.count, IcmSetVelocities<R>{p.vel.data(), start_.data(), s.group});
    }

    // The fluid's velocity field and its last advection (three grids of faces each), so that a run
    // continued from a checkpoint is the run that went on.
    std::vector<double> state() const override {
        std::vector<double> out;
        if (vel_.size() == 0) return out;
        std::vector<R> held(vel_.size());
        for (const auto* field : {&vel_, &advection_}) {
            backend_.download(*field, held.data(), held.size());
            out.insert(out.end(), held.begin(), held.end());
        }
        out.push_back(firstStep_ ? 1.0 : 0.0);
        return out;
    }
    void restore(const std::vector<double>& saved) override {
        restored_ = saved;
        if (fft_) apply_restored();
    }

private:
    // The grid for the box the integrator starts with (a box that changes afterwards is refused),
    // and the fluid at equilibrium: each face's velocity drawn with variance kT / (rho dV), then
    // projected onto divergence-free fields (the mean removed where removeTotalMomentum).
    void prepare(const Particles<B, R>& p) {
        const IntegratorScope& s = this->scope();
        const std::array<double, 3> box = {double(p.box.length.x), double(p.box.length.y), double(p.box.length.z)};
        if (fft_) {
            refuse_changed_box(s, box.data(), box_.data(), 3,
                               "[\"FluctuatingHydrodynamics\", \"IncompressibleInertialCoupling\"]", "keeps the fluid");
        } else {
            require_periodic_box(box, s.path + ".type", "the inertial coupling method's fluid");
            box_ = box;
            const std::array<int, 3> n = icm_cells(values_, box, s.path);
            grid_.cells = FftGrid{n[0], n[1], n[2]};
            grid_.length = p.box.length;
            grid_.spacing = Vec3<R>{R(box[0] / n[0]), R(box[1] / n[1]), R(box[2] / n[2])};
            const int64_t points = grid_.cells.points();
            fft_ = std::make_unique<typename B::template Fft3d<R>>(backend_, grid_.cells);
            bins_ = std::make_unique<LineBins<B>>(backend_, n[1] * n[2]);
            backend_.resize(vel_, static_cast<size_t>(3 * points));
            backend_.resize(rhs_, static_cast<size_t>(3 * points));
            backend_.resize(advection_, static_cast<size_t>(3 * points));
            backend_.resize(stress_, static_cast<size_t>(6 * points));
            backend_.resize(spectrum_, static_cast<size_t>(3 * grid_.cells.spectrum_points()));
            if (s.log)
                s.log->info(s.name + ": inertial coupling fluid of " + std::to_string(n[0]) + " x " + std::to_string(n[1]) +
                            " x " + std::to_string(n[2]) + " cells, hydrodynamic radius " +
                            std::to_string(kPeskin3RadiusOverSpacing * box[0] / n[0]));
            if (!apply_restored()) {
                const double cellVolume = box[0] * box[1] * box[2] / double(points);
                backend_.for_each(points, DrawStaggeredNormals<R>{rhs_.data(), points, 3, p.noise.seed,
                                                                  static_cast<uint64_t>(NoisePurpose::initialVelocities) << 48,
                                                                  p.now()});
                backend_.for_each(3 * points, IcmScaleField<R>{rhs_.data(), R(std::sqrt(s.kT / (density_ * cellVolume)))});
                solve(R(0));
            }
        }
        backend_.resize(start_, static_cast<size_t>(3 * p.count));
        backend_.resize(midOld_, static_cast<size_t>(3 * p.count));
        backend_.resize(midNew_, static_cast<size_t>(3 * p.count));
        backend_.resize(probeVectors_, static_cast<size_t>(3 * p.count));
        backend_.resize(probe_, static_cast<size_t>(p.count));
    }

    // The saved fluid, where restore gave one for this grid: true when applied.
    bool apply_restored() {
        const size_t faces = vel_.size();
        const bool fits = restored_.size() == 2 * faces + 1;
        if (fits) {
            std::vector<R> held(restored_.begin(), restored_.begin() + faces);
            backend_.upload(vel_, held.data(), faces);
            held.assign(restored_.begin() + faces, restored_.end() - 1);
            backend_.upload(advection_, held.data(), faces);
            firstStep_ = restored_.back() != 0.0;
        }
        restored_.clear();
        return fits;
    }

    // rhs -> vel: transform, solve and project, transform back.
    void solve(R viscousScale) {
        const int64_t points = grid_.cells.points(), spectrumPoints = grid_.cells.spectrum_points();
        for (int d = 0; d < 3; ++d) fft_->forward(rhs_.data() + d * points, spectrum_.data() + d * spectrumPoints);
        backend_.for_each(spectrumPoints, InertialFluidSolve<R>{spectrum_.data(), grid_, viscousScale, removeTotalMomentum_});
        for (int d = 0; d < 3; ++d) fft_->inverse(spectrum_.data() + d * spectrumPoints, vel_.data() + d * points);
    }

    void interpolate(const Particles<B, R>& p, const Real4<R>* positions, const R* field, R* out) {
        backend_.for_each(p.count, InertialFluidInterpolate<R>{positions, this->scope().group, grid_, field, out});
    }

    template <class Vectors>
    void spread(const Particles<B, R>& p, const Real4<R>* positions, const Vectors& vectors, R scale) {
        bins_->sort(p.count, StaggeredParticleLine<R>{positions, this->scope().group, grid_});
        backend_.for_each(int64_t(grid_.cells.ny) * grid_.cells.nz,
                          InertialFluidSpreadLine<R, Vectors>{positions, vectors, bins_->order(), bins_->line_start(), grid_,
                                                          scale, rhs_.data()});
    }

    // (dt / rho) (kT / delta) [S(q + delta/2 W') - S(q - delta/2 W')] W', delta = 1e-6 a (1e-4 a in
    // single precision), as UAMMD.
    void add_thermal_drift(Particles<B, R>& p, double cellVolume) {
        const IntegratorScope& s = this->scope();
        const double radius = kPeskin3RadiusOverSpacing * double(grid_.spacing.x);
        const double delta = (sizeof(R) == sizeof(double) ? 1e-6 : 1e-4) * radius;
        for (R sign : {R(1), R(-1)}) {
            backend_.for_each(p.count, IcmDriftProbe<R>{p.pos.data(), s.group, p.noise, p.now(), R(0.5 * delta), sign, p.box,
                                                        probe_.data(), probeVectors_.data()});
            spread(p, probe_.data(), FlatVectors<R>{probeVectors_.data()},
                   R(s.timeStep * s.kT / (density_ * cellVolume * delta)));
        }
    }

    const B& backend_;
    ParameterValues values_;
    double viscosity_, density_;
    bool sumThermalDrift_, removeTotalMomentum_;
    bool firstStep_ = true;
    std::array<double, 3> box_{};
    StaggeredGrid<R> grid_{};
    std::unique_ptr<typename B::template Fft3d<R>> fft_;
    std::unique_ptr<LineBins<B>> bins_;
    std::vector<double> restored_;
    typename B::template Buffer<R> vel_, rhs_, advection_, stress_, start_, midOld_, midNew_, probeVectors_;
    typename B::template Buffer<Real4<R>> probe_;
    typename B::template Buffer<Complex<R>> spectrum_;
};

}  // namespace structmd
