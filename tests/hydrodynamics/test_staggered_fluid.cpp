// The inertial coupling method's fluid below the integrator (hydrodynamics/staggered_fluid.hpp), on
// the CPU backend: the Peskin kernel's sums, spreading that puts in exactly the momentum of the
// forces and is the adjoint of interpolation, a forcing step whose viscous, random and advective parts
// carry no net momentum, a solve that leaves the field divergence-free (checked with the divergence
// written out here in real space) and keeps or removes the mean as asked, and the fluctuating fluid
// alone holding every Fourier mode at k_B T / (rho dV) per transverse direction (checked with the
// transforms of the field, 2 k_B T / (rho dV) summed over the components of each k != 0).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "backends/cpu/cpu_fft.hpp"
#include "hydrodynamics/staggered_fluid.hpp"
#include "neighbour/line_bins.hpp"
#include "hydrodynamics/gaussian_spreading.hpp"

namespace structmd {
namespace {

StaggeredGrid<double> cube(int n, double length) {
    StaggeredGrid<double> g;
    g.cells = FftGrid{n, n, n};
    g.length = Vec3<double>{length, length, length};
    g.spacing = Vec3<double>{length / n, length / n, length / n};
    return g;
}

std::vector<double> gaussian(size_t n, unsigned seed) {
    std::mt19937 engine(seed);
    std::normal_distribution<double> normal;
    std::vector<double> out(n);
    for (double& x : out) x = normal(engine);
    return out;
}

// The discrete divergence at every cell centre: sum_d (v_d(r) - v_d(r - e_d)) / h.
double max_divergence(const StaggeredGrid<double>& g, const double* v) {
    const int n = g.cells.nx;
    const int64_t points = g.cells.points();
    double worst = 0.0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const int64_t c = g.cells.index(x, y, z);
                const double div = (v[c] - v[g.at(x, y, z, -1, 0, 0)]) / g.spacing.x +
                                   (v[points + c] - v[points + g.at(x, y, z, 0, -1, 0)]) / g.spacing.y +
                                   (v[2 * points + c] - v[2 * points + g.at(x, y, z, 0, 0, -1)]) / g.spacing.z;
                worst = std::max(worst, std::fabs(div));
            }
    return worst;
}

struct Fluid {
    CpuBackend backend{2};
    StaggeredGrid<double> grid;
    CpuFft3d<double> fft;
    HostBuffer<double> vel, rhs, advection, stress;
    HostBuffer<Complex<double>> spectrum;

    explicit Fluid(int n, double length) : grid(cube(n, length)), fft(backend, grid.cells) {
        const int64_t p = grid.cells.points();
        backend.resize(vel, 3 * p);
        backend.resize(rhs, 3 * p);
        backend.resize(advection, 3 * p);
        backend.resize(stress, 6 * p);
        backend.resize(spectrum, 3 * grid.cells.spectrum_points());
        backend.fill(vel, 0.0);
        backend.fill(advection, 0.0);
    }
    int64_t points() const { return grid.cells.points(); }
    void solve(double viscousScale, bool removeMean) {
        const int64_t p = points(), s = grid.cells.spectrum_points();
        for (int d = 0; d < 3; ++d) fft.forward(rhs.data() + d * p, spectrum.data() + d * s);
        backend.for_each(s, InertialFluidSolve<double>{spectrum.data(), grid, viscousScale, removeMean});
        for (int d = 0; d < 3; ++d) fft.inverse(spectrum.data() + d * s, vel.data() + d * p);
    }
};

TEST(PeskinThreePoint, SumsToOneWithSquaresSummingToOneHalfAndNoFirstMoment) {
    for (double r = -0.5; r <= 0.5; r += 0.03125) {
        double sum = 0, squares = 0, moment = 0;
        for (int j = -3; j <= 3; ++j) {
            const double w = peskin3(r - j);
            sum += w;
            squares += w * w;
            moment += w * (r - j);
        }
        EXPECT_NEAR(sum, 1.0, 1e-14);
        EXPECT_NEAR(squares, 0.5, 1e-14);
        EXPECT_NEAR(moment, 0.0, 1e-14);
    }
}

TEST(StaggeredFluid, SpreadingPutsInTheForcesAndIsTheAdjointOfInterpolation) {
    Fluid f(6, 7.5);
    const int count = 9;
    std::mt19937 engine(3);
    std::uniform_real_distribution<double> coordinate(-3.75, 3.75);
    HostBuffer<Real4<double>> pos, force;
    f.backend.resize(pos, count);
    f.backend.resize(force, count);
    const std::vector<double> forces = gaussian(3 * count, 4);
    for (int i = 0; i < count; ++i) {
        pos.data()[i] = {coordinate(engine), coordinate(engine), coordinate(engine), 0.0};
        force.data()[i] = {forces[3 * i], forces[3 * i + 1], forces[3 * i + 2], 0.0};
    }
    LineBins<CpuBackend> bins(f.backend, 36);
    bins.sort(count, StaggeredParticleLine<double>{pos.data(), nullptr, f.grid});
    f.backend.fill(f.rhs, 0.0);
    f.backend.for_each(36, InertialFluidSpreadLine<double, Real4Vectors<double>>{pos.data(), {force.data()}, bins.order(),
                                                                             bins.line_start(), f.grid, 1.0, f.rhs.data()});
    const int64_t p = f.points();
    for (int c = 0; c < 3; ++c) {
        double onGrid = 0, given = 0;
        for (int64_t k = 0; k < p; ++k) onGrid += f.rhs.data()[c * p + k];
        for (int i = 0; i < count; ++i) given += forces[3 * i + c];
        EXPECT_NEAR(onGrid, given, 1e-12);
    }
    // <J v, F> = <v, S' F>, S' the spreading without 1 / dV.
    const std::vector<double> v = gaussian(3 * p, 5);
    f.backend.upload(f.vel, v.data(), v.size());
    HostBuffer<double> u;
    f.backend.resize(u, 3 * count);
    f.backend.for_each(count, InertialFluidInterpolate<double>{pos.data(), nullptr, f.grid, f.vel.data(), u.data()});
    double left = 0, right = 0;
    for (int k = 0; k < 3 * count; ++k) left += u.data()[k] * forces[k];
    for (int64_t k = 0; k < 3 * p; ++k) right += v[k] * f.rhs.data()[k];
    EXPECT_NEAR(left, right, 1e-11 * std::fabs(right));
    // A brute-force interpolation of particle 0's x velocity: every x face, its weight.
    double brute = 0;
    const Real4<double> q = pos.data()[0];
    const double h = 7.5 / 6;
    for (int z = 0; z < 6; ++z)
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 6; ++x) {
                auto image = [](double d) { return d - 7.5 * std::round(d / 7.5); };
                const double w = peskin3(image((x + 1.0) * h - 3.75 - q.x) / h) *
                                 peskin3(image((y + 0.5) * h - 3.75 - q.y) / h) *
                                 peskin3(image((z + 0.5) * h - 3.75 - q.z) / h);
                brute += w * v[f.grid.cells.index(x, y, z)];
            }
    EXPECT_NEAR(u.data()[0], brute, 1e-13);
}

TEST(StaggeredFluid, TheForcingCarriesNoNetMomentumAndTheSolveLeavesNoDivergence) {
    Fluid f(8, 8.0);
    const int64_t p = f.points();
    const std::vector<double> v = gaussian(3 * p, 6), w = gaussian(6 * p, 7);
    f.backend.upload(f.vel, v.data(), v.size());
    f.backend.upload(f.stress, w.data(), w.size());
    f.backend.for_each(p, StaggeredFluidForcing<double>{f.vel.data(), f.stress.data(), f.advection.data(), f.rhs.data(),
                                                        f.grid, 0.3, 0.7, 0.2, 1.3, true});
    for (int c = 0; c < 3; ++c) {
        double change = 0;
        for (int64_t k = 0; k < p; ++k) change += f.rhs.data()[c * p + k] - v[c * p + k];
        EXPECT_NEAR(change, 0.0, 1e-10);
    }
    std::vector<double> mean(3, 0.0);
    for (int c = 0; c < 3; ++c)
        for (int64_t k = 0; k < p; ++k) mean[c] += f.rhs.data()[c * p + k] / double(p);
    f.solve(0.4, false);
    EXPECT_LT(max_divergence(f.grid, f.vel.data()), 1e-12);
    for (int c = 0; c < 3; ++c) {
        double kept = 0;
        for (int64_t k = 0; k < p; ++k) kept += f.vel.data()[c * p + k] / double(p);
        EXPECT_NEAR(kept, mean[c], 1e-13);
    }
    // The projection alone is idempotent; with the mean removed, none is left.
    f.backend.upload(f.rhs, f.vel.data(), 3 * p);
    std::vector<double> once(f.vel.data(), f.vel.data() + 3 * p);
    f.solve(0.0, true);
    for (int c = 0; c < 3; ++c) {
        double left = 0;
        for (int64_t k = 0; k < p; ++k) {
            left += f.vel.data()[c * p + k];
            EXPECT_NEAR(f.vel.data()[c * p + k], once[c * p + k] - mean[c], 1e-12);
        }
        EXPECT_NEAR(left, 0.0, 1e-11);
    }
}

TEST(StaggeredFluid, EveryFluidModeHoldsKTOverRhoDVPerTransverseDirection) {
    // 8^3 cells of side 1.25, rho 1.1, eta 0.9, kT 1e-3 (velocities of 0.03: advection small), dt 0.4.
    const int n = 8;
    const double length = 10.0, rho = 1.1, eta = 0.9, kT = 1e-3, dt = 0.4;
    Fluid f(n, length);
    const int64_t p = f.points(), s = f.grid.cells.spectrum_points();
    const double dV = std::pow(length / n, 3);
    const double viscous = 0.5 * dt * eta / rho, noise = std::sqrt(2 * kT * eta * dt / dV) / rho;
    HostBuffer<Complex<double>> modes;
    f.backend.resize(modes, 3 * s);
    const int hx = f.grid.cells.half_x();
    // The modes split at |D|^2 h^2 = 6 into a low and a high half, each checked on its own.
    std::vector<double> energy(s, 0.0);
    const int samples = 300, stride = 8;
    StepClock clock;
    for (int step = 0; step < 200 + samples * stride; ++step) {
        clock.step = step;
        f.backend.for_each(p, DrawStaggeredNormals<double>{f.stress.data(), p, 6, 11, 5ull << 48, ClockView{&clock}});
        f.backend.for_each(p, StaggeredFluidForcing<double>{f.vel.data(), f.stress.data(), f.advection.data(),
                                                            f.rhs.data(), f.grid, viscous, noise, dt / rho, rho, step == 0});
        f.solve(viscous, true);
        if (step >= 200 && (step - 200) % stride == 0) {
            for (int d = 0; d < 3; ++d) f.fft.forward(f.vel.data() + d * p, modes.data() + d * s);
            for (int64_t k = 0; k < s; ++k)
                for (int d = 0; d < 3; ++d) {
                    const Complex<double> m = modes.data()[d * s + k];
                    energy[k] += (m.re * m.re + m.im * m.im) / double(p) / samples;
                }
        }
    }
    const double expected = 2 * kT / (rho * dV);
    EXPECT_LT(energy[0], 1e-20);
    double low = 0, high = 0;
    int lowCount = 0, highCount = 0;
    for (int64_t k = 1; k < s; ++k) {
        const int x = int(k % hx), y = int((k / hx) % n), z = int(k / (int64_t(hx) * n));
        double norm2 = 0;
        for (int m : {x, y, z}) norm2 += 4 * std::pow(std::sin(M_PI * m / n), 2);
        // x = 0 and x = n/2 hold their own conjugates: counted once like every other mode.
        if (norm2 < 6.0) {
            low += energy[k] / expected;
            ++lowCount;
        } else {
            high += energy[k] / expected;
            ++highCount;
        }
    }
    // Each mode's energy over 300 samples (about 3 steps of correlation, 8 apart) has a relative
    // standard error near sqrt(1 / (2 * 300)) = 4%; averaged over >= 100 modes, below 0.4%: 2% is 5 of them.
    EXPECT_GT(lowCount, 100);
    EXPECT_GT(highCount, 100);
    EXPECT_NEAR(low / lowCount, 1.0, 0.02);
    EXPECT_NEAR(high / highCount, 1.0, 0.02);
}

}  // namespace
}  // namespace structmd
