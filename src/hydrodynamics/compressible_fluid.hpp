#pragma once
// The compressible fluctuating fluid of the compressible inertial coupling method (integrators/
// fluctuating_hydrodynamics_compressible_icm.hpp; Balboa Usabiaga, Pagonabarraga & Delgado-Buscalioni,
// J. Comput. Phys. 235, 701 (2013), appendix A), on the staggered grid of staggered_fluid.hpp in a
// triply periodic box: the density rho on the cell centres, the momentum g = rho v and the velocity v
// on the faces (component alpha on the cells' upper faces along alpha). The isothermal Navier-Stokes
// equations in conservative form,
//   d rho / dt = -D g
//   d g / dt   = -D(g v^T) - G(c^2 rho) + eta L v + (zeta + eta/3) G D v + D Z + f,
// c the speed of sound (the equation of state p = c^2 rho), eta and zeta the shear and bulk
// viscosities, f the force density the particles spread, Z the random stress with
//   <Z_ab Z_cd> = (2 kT / (dV dt)) [eta (d_ac d_bd + d_ad d_bc) + (zeta - 2 eta / 3) d_ab d_cd].
// Spatially: D and G the staggered divergence (faces to centres) and gradient (centres to faces), L
// the seven-point Laplacian of each component, the face density (rho_r + rho_{r+alpha}) / 2 that turns
// momentum into velocity, and the advective flux g_b v_a at the cell centres (b = a, both averaged
// along a) and at the edges r + e_a/2 + e_b/2 (v_a averaged along b, g_b along a). Every term is a
// difference of fluxes, so the sums of rho and g over the box change only by the forcing's.
//
// In time: the explicit three-stage Runge-Kutta scheme of Donev, Vanden-Eijnden, Garcia & Bell
// (CAMCoS 5, 149 (2010)), U = (rho, g),
//   U' = U^n + dU(U^n, W_A - sqrt(3) W_B)
//   U'' = 3/4 U^n + 1/4 [U' + dU(U', W_A + sqrt(3) W_B)]
//   U^{n+1} = 1/3 U^n + 2/3 [U'' + dU(U'', W_A)],
// dU the right-hand sides times dt, W_A and W_B independent random stresses of the step (their
// combination over the stages adds W_A alone: the noise of one Euler step) and f held over the step.
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/hd.hpp"
#include "hydrodynamics/staggered_fluid.hpp"
#include "state/step_clock.hpp"

namespace structmd {

// One time level of the fluid: seven grids of cells one after the other, the density, the three
// components of the momentum, the three of the velocity (the layout InertialFluidInterpolate reads).
inline constexpr int kCompressibleLevelGrids = 7;
inline constexpr int kCompressibleMomentumGrid = 1;
inline constexpr int kCompressibleVelocityGrid = 4;
// The random stresses of a step: W_A then W_B, six grids each (xx, yy, zz at the cell centres; xy,
// xz, yz at the cells' upper edges, as DrawStaggeredNormals keys them).
inline constexpr int kCompressibleStressGrids = 12;

// Turns the standard normal numbers of W_A and W_B into the random stresses, times sqrt(dt):
//   Z = cross (W + W^T) / sqrt(2) + trace tr(W) I,   cross = sqrt(2 eta kT dt / dV),
//   trace = sqrt(zeta kT dt / (3 dV)) - cross / 3,
// (W + W^T) / sqrt(2) having variance 2 on the diagonal and 1 off it: the traceless part carries the
// shear viscosity's covariance and the trace the bulk viscosity's.
template <class R>
struct CompressibleFluidStochasticStress {
    R* stress;  // kCompressibleStressGrids grids, in place
    int64_t points;
    R cross, trace;
    SMD_HD void operator()(int64_t cell) const {
        const R sqrt2 = R(1.4142135623730951);
        for (int set = 0; set < 2; ++set) {
            R* w = stress + int64_t(6 * set) * points + cell;
            const R diagonal[3] = {sqrt2 * w[0], sqrt2 * w[points], sqrt2 * w[2 * points]};
            const R sum = diagonal[0] + diagonal[1] + diagonal[2];
            for (int a = 0; a < 3; ++a) w[a * points] = cross * diagonal[a] + trace * sum;
            for (int pair = 3; pair < 6; ++pair) w[pair * points] *= cross;
        }
    }
};

// One stage of the Runge-Kutta step for one cell:
//   U^C = weightA U^A + weightB [U^B + dU(U^B, Z_A + noiseWeightB Z_B)],
// the right-hand side evaluated at level B. Writes the density and the momentum of level C (the
// velocity follows in CompressibleFluidVelocity, once every density of level C is known). Level A is
// read at this cell alone, so it may be level C; level B must not be.
template <class R>
struct CompressibleFluidStage {
    const R* levelA;
    const R* levelB;
    R* levelC;
    const R* forcing;  // three grids of force density; null: none
    const R* stress;   // kCompressibleStressGrids grids; null: no noise
    StaggeredGrid<R> grid;
    R weightA, weightB, noiseWeightB;
    R dt, shearViscosity, longitudinalViscosity;  // eta and zeta + eta/3
    R soundSpeedSquared;

    SMD_HD SMD_INLINE R at(int field, int x, int y, int z, const int* d) const {
        return levelB[field * grid.cells.points() + grid.at(x, y, z, d[0], d[1], d[2])];
    }
    SMD_HD SMD_INLINE R random_stress(int component, int x, int y, int z, const int* d) const {
        const int64_t points = grid.cells.points();
        const int64_t i = grid.at(x, y, z, d[0], d[1], d[2]);
        return stress[component * points + i] + noiseWeightB * stress[(6 + component) * points + i];
    }
    // (D v) at cell r + d: sum_b (v_b(r + d) - v_b(r + d - e_b)) / h_b.
    SMD_HD SMD_INLINE R velocity_divergence(int x, int y, int z, const int* d) const {
        R sum = R(0);
        for (int b = 0; b < 3; ++b) {
            int down[3] = {d[0], d[1], d[2]};
            down[b] -= 1;
            sum += (at(kCompressibleVelocityGrid + b, x, y, z, d) - at(kCompressibleVelocityGrid + b, x, y, z, down)) /
                   grid.h(b);
        }
        return sum;
    }

    SMD_HD void operator()(int64_t cell) const {
        const FftGrid& g = grid.cells;
        const int64_t points = g.points();
        const int x = static_cast<int>(cell % g.nx), y = static_cast<int>((cell / g.nx) % g.ny),
                  z = static_cast<int>(cell / (int64_t(g.nx) * g.ny));
        const int zero[3] = {0, 0, 0};
        const int M = kCompressibleMomentumGrid, V = kCompressibleVelocityGrid;

        R densityIncrement = R(0);
        for (int a = 0; a < 3; ++a) {
            int down[3] = {0, 0, 0};
            down[a] = -1;
            densityIncrement -= (at(M + a, x, y, z, zero) - at(M + a, x, y, z, down)) / grid.h(a);
        }
        densityIncrement *= dt;

        R momentum[3];
        const R divergenceHere = velocity_divergence(x, y, z, zero);
        for (int a = 0; a < 3; ++a) {
            int alongA[3] = {0, 0, 0};
            alongA[a] = 1;
            const R ha = grid.h(a);
            const R va = at(V + a, x, y, z, zero);
            R advection = R(0), laplacian = R(0), noise = R(0);
            for (int b = 0; b < 3; ++b) {
                int up[3] = {0, 0, 0}, down[3] = {0, 0, 0};
                up[b] = 1;
                down[b] = -1;
                const R hb = grid.h(b);
                const R vUp = at(V + a, x, y, z, up), vDown = at(V + a, x, y, z, down);
                laplacian += (vUp - R(2) * va + vDown) / (hb * hb);
                if (b == a) {
                    // The centres of cells r + e_a and r.
                    const R ga = at(M + a, x, y, z, zero);
                    const R fluxUp = R(0.25) * (ga + at(M + a, x, y, z, up)) * (va + vUp);
                    const R fluxDown = R(0.25) * (at(M + a, x, y, z, down) + ga) * (vDown + va);
                    advection += (fluxUp - fluxDown) / hb;
                    if (stress) noise += (random_stress(a, x, y, z, alongA) - random_stress(a, x, y, z, zero)) / hb;
                } else {
                    // The edges r + e_a/2 +- e_b/2.
                    int alongADown[3] = {0, 0, 0};
                    alongADown[a] = 1;
                    alongADown[b] = -1;
                    const R fluxUp = R(0.25) * (va + vUp) * (at(M + b, x, y, z, zero) + at(M + b, x, y, z, alongA));
                    const R fluxDown =
                        R(0.25) * (vDown + va) * (at(M + b, x, y, z, down) + at(M + b, x, y, z, alongADown));
                    advection += (fluxUp - fluxDown) / hb;
                    if (stress) {
                        const int pair = a + b == 1 ? 3 : a + b == 2 ? 4 : 5;  // xy, xz, yz
                        noise += (random_stress(pair, x, y, z, zero) - random_stress(pair, x, y, z, down)) / hb;
                    }
                }
            }
            // c^2 (rho_{r+e_a} - rho_r): the difference first, so that a uniform density has none at all.
            const R pressureGradient = soundSpeedSquared * (at(0, x, y, z, alongA) - at(0, x, y, z, zero)) / ha;
            const R divergenceGradient = (velocity_divergence(x, y, z, alongA) - divergenceHere) / ha;
            R increment = dt * (-advection - pressureGradient + shearViscosity * laplacian +
                                longitudinalViscosity * divergenceGradient) +
                          noise;
            if (forcing) increment += dt * forcing[a * points + cell];
            momentum[a] = weightB * (levelB[(M + a) * points + cell] + increment);
            if (weightA != R(0)) momentum[a] += weightA * levelA[(M + a) * points + cell];
        }
        R density = weightB * (levelB[cell] + densityIncrement);
        if (weightA != R(0)) density += weightA * levelA[cell];
        levelC[cell] = density;
        for (int a = 0; a < 3; ++a) levelC[(M + a) * points + cell] = momentum[a];
    }
};

// v_a = g_a / ((rho_r + rho_{r+e_a}) / 2) on every face of one cell.
template <class R>
struct CompressibleFluidVelocity {
    R* level;
    StaggeredGrid<R> grid;
    SMD_HD void operator()(int64_t cell) const {
        const FftGrid& g = grid.cells;
        const int64_t points = g.points();
        const int x = static_cast<int>(cell % g.nx), y = static_cast<int>((cell / g.nx) % g.ny),
                  z = static_cast<int>(cell / (int64_t(g.nx) * g.ny));
        for (int a = 0; a < 3; ++a) {
            const int64_t next = grid.at(x, y, z, a == 0, a == 1, a == 2);
            const R faceDensity = R(0.5) * (level[cell] + level[next]);
            level[(kCompressibleVelocityGrid + a) * points + cell] =
                level[(kCompressibleMomentumGrid + a) * points + cell] / faceDensity;
        }
    }
};

// The fluid at rest: rho = density, g = v = 0.
template <class R>
struct CompressibleFluidAtRest {
    R* level;
    int64_t points;
    R density;
    SMD_HD void operator()(int64_t i) const { level[i] = i < points ? density : R(0); }
};

// The fluid's state and its step, on backend B (the particles' side is the integrator's).
template <class B, class R>
class CompressibleFluid {
public:
    struct Properties {
        double shearViscosity = 0.0, bulkViscosity = 0.0, speedOfSound = 0.0, density = 0.0;
    };

    CompressibleFluid(const B& backend, const StaggeredGrid<R>& grid, const Properties& properties)
        : backend_(backend), grid_(grid), properties_(properties) {
        const size_t level = static_cast<size_t>(kCompressibleLevelGrids * points());
        for (auto* buffer : {&current_, &first_, &second_}) backend_.resize(*buffer, level);
        backend_.resize(forcing_, static_cast<size_t>(3 * points()));
        backend_.resize(stress_, static_cast<size_t>(kCompressibleStressGrids * points()));
        clear_forcing();
        start_at_rest();
    }

    int64_t points() const { return grid_.cells.points(); }
    const StaggeredGrid<R>& grid() const { return grid_; }
    double cell_volume() const { return double(grid_.spacing.x) * grid_.spacing.y * grid_.spacing.z; }

    void start_at_rest() {
        backend_.for_each(int64_t(current_.size()), CompressibleFluidAtRest<R>{current_.data(), points(), R(properties_.density)});
    }
    // The level of step n: density, momentum and velocity (kCompressibleLevelGrids grids).
    R* level() { return current_.data(); }
    const R* level() const { return current_.data(); }
    const R* velocity() const { return current_.data() + kCompressibleVelocityGrid * points(); }
    // The force density f of the coming step (three grids): cleared by clear_forcing, added to by the caller.
    R* forcing() { return forcing_.data(); }
    void clear_forcing() { backend_.fill(forcing_, R(0)); }
    // After the caller wrote a level's density and momentum: its velocity.
    void update_velocity() { backend_.for_each(points(), CompressibleFluidVelocity<R>{current_.data(), grid_}); }

    // U^n -> U^{n+1} over dt with the forcing held. At kT > 0 the random stresses are drawn from the
    // noise seed, the stream (W_A's; W_B's has bit 47 set, above any cell's) and the step on the
    // clock (read on the backend, so a recorded step draws anew).
    void step(double dt, double kT, uint64_t seed, uint64_t stream, ClockView now) {
        const bool noisy = kT > 0.0;
        if (noisy) {
            const int64_t n = points();
            backend_.for_each(n, DrawStaggeredNormals<R>{stress_.data(), n, 6, seed, stream, now});
            backend_.for_each(n, DrawStaggeredNormals<R>{stress_.data() + 6 * n, n, 6, seed, stream | (uint64_t(1) << 47), now});
            const double dV = cell_volume(), eta = properties_.shearViscosity;
            const double cross = std::sqrt(2.0 * eta * kT * dt / dV);
            const double trace = std::sqrt(properties_.bulkViscosity * kT * dt / (3.0 * dV)) - cross / 3.0;
            backend_.for_each(n, CompressibleFluidStochasticStress<R>{stress_.data(), n, R(cross), R(trace)});
        }
        const R* stress = noisy ? stress_.data() : nullptr;
        const R root3 = R(1.7320508075688772);
        stage(current_.data(), current_.data(), first_.data(), R(0), R(1), -root3, dt, stress);
        stage(current_.data(), first_.data(), second_.data(), R(0.75), R(0.25), root3, dt, stress);
        stage(current_.data(), second_.data(), current_.data(), R(1) / R(3), R(2) / R(3), R(0), dt, stress);
    }

    // The level of step n, for a checkpoint.
    std::vector<double> save() const {
        std::vector<R> held(current_.size());
        backend_.download(current_, held.data(), held.size());
        return std::vector<double>(held.begin(), held.end());
    }
    // Restores what save() gave for a grid of the same size: true when it fits.
    bool load(const std::vector<double>& saved) {
        if (saved.size() != current_.size()) return false;
        std::vector<R> held(saved.begin(), saved.end());
        backend_.upload(current_, held.data(), held.size());
        return true;
    }

private:
    void stage(const R* a, const R* b, R* c, R weightA, R weightB, R noiseWeightB, double dt, const R* stress) {
        const double eta = properties_.shearViscosity;
        const double c2 = properties_.speedOfSound * properties_.speedOfSound;
        backend_.for_each(points(), CompressibleFluidStage<R>{a, b, c, forcing_.data(), stress, grid_, weightA, weightB,
                                                              noiseWeightB, R(dt), R(eta),
                                                              R(properties_.bulkViscosity + eta / 3.0), R(c2)});
        backend_.for_each(points(), CompressibleFluidVelocity<R>{c, grid_});
    }

    const B& backend_;
    StaggeredGrid<R> grid_;
    Properties properties_;
    typename B::template Buffer<R> current_, first_, second_, forcing_, stress_;
};

}  // namespace structmd
