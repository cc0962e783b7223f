// The compressible inertial coupling method's fluid below the integrator (hydrodynamics/
// compressible_fluid.hpp), on the CPU backend, against the linearised equations solved by hand:
// - mass and momentum are conserved to rounding (the noise too), the forcing adds dt sum f per step,
//   and a uniform fluid at rest stays exactly at rest;
// - a small density wave rho_0 eps cos(k x) oscillates and decays as the damped oscillator
//   rho'' + nu_l kk^2 rho' + c^2 kk^2 rho = 0, kk = 2 sin(k h / 2) / h the staggered grid's wave
//   number, nu_l = (4 eta / 3 + zeta) / rho_0 (the second differences of the grid are exact on it);
// - a shear wave v_y = eps sin(k x) decays as exp(-(eta / rho_0) kk^2 t);
// - with noise, the fluid reaches the discrete equilibrium: each cell's density fluctuation has
//   variance rho kT / (c^2 dV) and each face's velocity kT / (rho dV) (times 1 - 1/N: the total mass
//   and momentum are fixed), so the static structure factor <|drho_k|^2> / N is rho kT / (c^2 dV) for
//   every k != 0 (checked apart on the low and the high half of the wave vectors);
//   and the longitudinal modes hold their kT / (rho dV) each, seen in the divergence D v, whose
//   variance is then (kT / (rho dV)) (1/N) sum_k |D_k|^2 = 6 kT / (rho dV h^2) (this one depends on
//   the bulk viscosity's share of the random stress).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "backends/cpu/cpu_fft.hpp"
#include "hydrodynamics/compressible_fluid.hpp"

namespace structmd {
namespace {

StaggeredGrid<double> box_of_cells(int nx, int ny, int nz, double h) {
    StaggeredGrid<double> g;
    g.cells = FftGrid{nx, ny, nz};
    g.length = Vec3<double>{nx * h, ny * h, nz * h};
    g.spacing = Vec3<double>{h, h, h};
    return g;
}

struct CompressibleBox {
    CpuBackend backend{2};
    CompressibleFluid<CpuBackend, double> fluid;
    StepClock clock;

    CompressibleBox(const StaggeredGrid<double>& grid, double eta, double zeta, double c, double rho)
        : fluid(backend, grid, {eta, zeta, c, rho}) {}
    int64_t points() const { return fluid.points(); }
    double* density() { return fluid.level(); }
    double* momentum(int a) { return fluid.level() + (kCompressibleMomentumGrid + a) * points(); }
    const double* velocity(int a) const { return fluid.velocity() + a * points(); }
    void step(double dt, double kT, uint64_t seed = 7) {
        fluid.step(dt, kT, seed, uint64_t(5) << 48, ClockView{&clock, 0, 0.0});
        clock.step += 1;
    }
    double sum(const double* field) const {
        double s = 0.0;
        for (int64_t i = 0; i < points(); ++i) s += field[i];
        return s;
    }
};

TEST(CompressibleFluid, AUniformFluidAtRestStaysExactlyAtRest) {
    CompressibleBox box(box_of_cells(6, 5, 4, 0.8), 0.7, 0.3, 1.9, 1.3);
    for (int s = 0; s < 20; ++s) box.step(0.05, 0.0);
    for (int64_t i = 0; i < box.points(); ++i) {
        ASSERT_EQ(box.density()[i], 1.3);
        for (int a = 0; a < 3; ++a) ASSERT_EQ(box.momentum(a)[i], 0.0);
    }
}

TEST(CompressibleFluid, MassAndMomentumAreConservedToRoundingAndTheForcingAddsItsImpulse) {
    CompressibleBox box(box_of_cells(6, 5, 4, 0.8), 0.7, 0.3, 1.9, 1.3);
    const int64_t p = box.points();
    std::mt19937 engine(5);
    std::normal_distribution<double> normal;
    for (int64_t i = 0; i < p; ++i) {
        box.density()[i] = 1.3 * (1.0 + 0.05 * normal(engine));
        for (int a = 0; a < 3; ++a) box.momentum(a)[i] = 0.05 * normal(engine);
    }
    box.fluid.update_velocity();
    const double mass = box.sum(box.density());
    double momentum[3], force[3];
    for (int a = 0; a < 3; ++a) momentum[a] = box.sum(box.momentum(a));
    // Without forcing, with noise: nothing changes the sums.
    const int steps = 50;
    const double dt = 0.02, kT = 1e-3;
    for (int s = 0; s < steps; ++s) box.step(dt, kT);
    EXPECT_NEAR(box.sum(box.density()), mass, 1e-13 * mass);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(box.sum(box.momentum(a)), momentum[a], 1e-13 * mass);
    // A forcing held over the steps adds dt sum f each step.
    for (int a = 0; a < 3; ++a) {
        momentum[a] = box.sum(box.momentum(a));
        for (int64_t i = 0; i < p; ++i) box.fluid.forcing()[a * p + i] = 0.1 * normal(engine);
        force[a] = box.sum(box.fluid.forcing() + a * p);
    }
    for (int s = 0; s < steps; ++s) box.step(dt, kT);
    EXPECT_NEAR(box.sum(box.density()), mass, 1e-13 * mass);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(box.sum(box.momentum(a)), momentum[a] + steps * dt * force[a], 1e-12 * mass);
    // Every velocity is its momentum over the face's density.
    for (int64_t i = 0; i < p; ++i) {
        const int64_t next = box.fluid.grid().at(static_cast<int>(i % 6), static_cast<int>(i / 6 % 5),
                                                 static_cast<int>(i / 30), 1, 0, 0);
        EXPECT_NEAR(box.velocity(0)[i], box.momentum(0)[i] / (0.5 * (box.density()[i] + box.density()[next])), 1e-15);
    }
}

// rho_0 eps cos(k x) along x on 16 x 4 x 4 cells: the density's cosine amplitude against the damped
// oscillator's, rho_0 eps e^{-Gamma t} (cos w t + (Gamma / w) sin w t), Gamma = nu_l kk^2 / 2,
// w = sqrt(c^2 kk^2 - Gamma^2), over a period and a half; for two pairs of viscosities.
TEST(CompressibleFluid, ADensityWaveOscillatesAtTheSoundSpeedDampedByTheLongitudinalViscosity) {
    const int n = 16;
    const double h = 0.5, rho = 1.2, c = 2.0, eps = 1e-6, dt = 0.01;
    const double k = 2 * M_PI / (n * h), kk = 2 * std::sin(k * h / 2) / h;
    for (const auto [eta, zeta] : {std::pair{0.05, 0.0}, std::pair{0.02, 0.1}}) {
        CompressibleBox box(box_of_cells(n, 4, 4, h), eta, zeta, c, rho);
        const int64_t p = box.points();
        auto x_of = [&](int64_t i) { return (static_cast<double>(i % n) + 0.5) * h; };
        for (int64_t i = 0; i < p; ++i) box.density()[i] = rho * (1.0 + eps * std::cos(k * x_of(i)));
        box.fluid.update_velocity();
        const double gamma = (4 * eta / 3 + zeta) / rho * kk * kk / 2, w = std::sqrt(c * c * kk * kk - gamma * gamma);
        const int steps = static_cast<int>(3 * M_PI / w / dt);
        for (int s = 1; s <= steps; ++s) {
            box.step(dt, 0.0);
            if (s % 50) continue;
            double amplitude = 0.0;
            for (int64_t i = 0; i < p; ++i) amplitude += (box.density()[i] - rho) * std::cos(k * x_of(i));
            amplitude *= 2.0 / double(p);
            const double t = s * dt;
            const double expected = rho * eps * std::exp(-gamma * t) * (std::cos(w * t) + gamma / w * std::sin(w * t));
            EXPECT_NEAR(amplitude, expected, 1e-5 * rho * eps) << "eta " << eta << " zeta " << zeta << " t " << t;
        }
    }
}

TEST(CompressibleFluid, AShearWaveDecaysByTheShearViscosity) {
    const int n = 16;
    const double h = 0.5, rho = 1.2, c = 2.0, eta = 0.08, zeta = 0.5, eps = 1e-6, dt = 0.01;
    const double k = 2 * M_PI / (n * h), kk = 2 * std::sin(k * h / 2) / h;
    CompressibleBox box(box_of_cells(n, 4, 4, h), eta, zeta, c, rho);
    const int64_t p = box.points();
    // v_y lives at x = (i + 1/2) h like the density.
    auto x_of = [&](int64_t i) { return (static_cast<double>(i % n) + 0.5) * h; };
    for (int64_t i = 0; i < p; ++i) box.momentum(1)[i] = rho * eps * std::sin(k * x_of(i));
    box.fluid.update_velocity();
    const int steps = 400;
    for (int s = 1; s <= steps; ++s) box.step(dt, 0.0);
    double amplitude = 0.0, density = 0.0;
    for (int64_t i = 0; i < p; ++i) {
        amplitude += box.velocity(1)[i] * std::sin(k * x_of(i));
        density = std::max(density, std::fabs(box.density()[i] - rho));
    }
    amplitude *= 2.0 / double(p);
    EXPECT_NEAR(amplitude, eps * std::exp(-eta / rho * kk * kk * steps * dt), 1e-9 * eps);
    EXPECT_LT(density, 1e-14);  // a transverse wave along x compresses nothing: no term moves mass
}

TEST(CompressibleFluid, TheFluctuatingFluidHoldsTheStructureFactorAndEquipartition) {
    // 8^3 cells of side 1, rho 1, c 1, kT 1e-4 (fluctuations of 1%: the equations stay linear), eta and
    // zeta 0.25, dt 0.05. 800 steps from rest (the slowest mode decays by e^-11 meanwhile), then 20
    // blocks of 300 steps sampled every 5. RK3's own bias (the linearised scheme's stationary
    // covariance, computed mode by mode) is below 0.1% here; 4 standard errors of the blocks and 0.3%
    // are allowed, and the standard error must stay below 1%: a random stress without its bulk part
    // would leave the divergence 40% short, one without the diagonal's sqrt(2) far more.
    const int n = 8;
    const double rho = 1.0, c = 1.0, kT = 1e-4, dt = 0.05, eta = 0.25, zeta = 0.25;
    CompressibleBox box(box_of_cells(n, n, n, 1.0), eta, zeta, c, rho);
    const int64_t p = box.points();
    const double dV = 1.0, N = double(p);
    const int blocks = 20, perBlock = 300, stride = 5;
    for (int s = 0; s < 800; ++s) box.step(dt, kT);
    std::vector<double> density(blocks, 0.0), velocity(blocks, 0.0), divergence(blocks, 0.0), lowK(blocks, 0.0),
        highK(blocks, 0.0);
    const StaggeredGrid<double>& g = box.fluid.grid();
    // The half spectrum's wave vectors split at |D|^2 h^2 = 6 (the mean of |D|^2 h^2 over k).
    CpuFft3d<double> fft(box.backend, g.cells);
    const int64_t spectrumPoints = g.cells.spectrum_points();
    const int hx = g.cells.half_x();
    std::vector<Complex<double>> spectrum(spectrumPoints);
    std::vector<double> fluctuation(p);
    std::vector<int> half(spectrumPoints, -1);  // 0 low, 1 high, -1 k = 0
    int halfCount[2] = {0, 0};
    for (int64_t at = 1; at < spectrumPoints; ++at) {
        const int m[3] = {static_cast<int>(at % hx), static_cast<int>(at / hx % n), static_cast<int>(at / (hx * n))};
        double norm2 = 0.0;
        for (int d = 0; d < 3; ++d) norm2 += std::pow(2 * std::sin(M_PI * m[d] / n), 2);
        half[at] = norm2 < 6.0 ? 0 : 1;
        halfCount[half[at]] += 1;
    }
    for (int b = 0; b < blocks; ++b) {
        for (int s = 1; s <= perBlock; ++s) {
            box.step(dt, kT);
            if (s % stride) continue;
            double dr = 0.0, vv = 0.0, dd = 0.0;
            for (int64_t i = 0; i < p; ++i) {
                const int x = static_cast<int>(i % n), y = static_cast<int>(i / n % n), z = static_cast<int>(i / (n * n));
                dr += (box.density()[i] - rho) * (box.density()[i] - rho);
                double div = 0.0;
                for (int a = 0; a < 3; ++a) {
                    vv += box.velocity(a)[i] * box.velocity(a)[i];
                    div += box.velocity(a)[i] - box.velocity(a)[g.at(x, y, z, -(a == 0), -(a == 1), -(a == 2))];
                }
                dd += div * div;
            }
            const double samples = double(perBlock / stride);
            for (int64_t i = 0; i < p; ++i) fluctuation[i] = box.density()[i] - rho;
            fft.forward(fluctuation.data(), spectrum.data());
            for (int64_t at = 1; at < spectrumPoints; ++at) {
                const double power = (spectrum[at].re * spectrum[at].re + spectrum[at].im * spectrum[at].im) / N;
                (half[at] == 0 ? lowK : highK)[b] += power / halfCount[half[at]] / samples;
            }
            density[b] += dr / N / samples;
            velocity[b] += vv / (3 * N) / samples;
            divergence[b] += dd / N / samples;
        }
    }
    auto check = [&](const std::vector<double>& values, double expected, const char* what) {
        double mean = 0.0, var = 0.0;
        for (double v : values) mean += v / blocks;
        for (double v : values) var += (v - mean) * (v - mean) / (blocks - 1);
        const double error = std::sqrt(var / blocks);
        EXPECT_LT(error, 0.01 * expected) << what;
        EXPECT_NEAR(mean, expected, 4 * error + 3e-3 * expected) << what << " error " << error;
    };
    check(density, rho * kT / (c * c * dV) * (1 - 1 / N), "density");
    check(lowK, rho * kT / (c * c * dV), "S(k), low k");
    check(highK, rho * kT / (c * c * dV), "S(k), high k");
    check(velocity, kT / (rho * dV) * (1 - 1 / N), "velocity");
    check(divergence, 6 * kT / (rho * dV), "divergence");
}

}  // namespace
}  // namespace structmd
