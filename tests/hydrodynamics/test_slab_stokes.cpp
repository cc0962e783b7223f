// The pieces of ["BDHIDoublyPeriodic","DPStokes"] below the engine (hydrodynamics/slab_stokes.hpp,
// slab_mesh.hpp): the band-limited kernel table against an independent quadrature on a tall grid,
// the slit's Stokes solve in single precision against double for a slit much thinner than the box,
// the slit's spreading weights (continuous across the mid-plane, zero on the walls), the spreading
// and average from the weights tabulated at placement against a direct sum over the grid, and the
// backends' batched plane transforms against one transform a plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <utility>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "backends/cpu/cpu_fft.hpp"
#include "hydrodynamics/slab_mesh.hpp"
#include "hydrodynamics/slab_spreading.hpp"
#include "hydrodynamics/slab_stokes.hpp"
#include "neighbour/line_bins.hpp"

namespace structmd {
namespace {

// (1/pi) int_0^Q f(q) dq by 5-point Gauss-Legendre on `panels` equal panels.
template <class F>
double gauss_legendre(const F& f, double band, int panels) {
    const double nodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
    const double weights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                               0.2369268850561891};
    const double width = band / panels;
    double sum = 0.0;
    for (int p = 0; p < panels; ++p)
        for (int k = 0; k < 5; ++k) sum += weights[k] * f(width * (p + 0.5 + 0.5 * nodes[k]));
    return sum * 0.5 * width / M_PI;
}

std::vector<SlabKernelEntry> kernel_table(const FftGrid& grid, double lengthX, double lengthY, double zSpacing) {
    std::vector<SlabKernelEntry> table(size_t(grid.half_x()) * grid.ny * grid.nz);
    const SlabKernelTable fill{grid, lengthX, lengthY, zSpacing, table.data()};
    for (int64_t i = 0; i < int64_t(table.size()); ++i) fill(i);
    return table;
}

TEST(SlabKernelTable, MatchesAnIndependentQuadratureOnATallGrid) {
    // 2001 nodes: at the largest separations cos(q s) turns 1000 times over the band.
    const FftGrid grid{8, 8, 2001};
    const double length = 8.0, hz = 0.5, band = M_PI / hz;
    std::vector<SlabKernelEntry> table(size_t(grid.half_x()) * grid.ny * grid.nz);
    const SlabKernelTable fill{grid, length, length, hz, table.data()};
    double worst = 0.0;
    for (int64_t at : {1, 3, 2 + 2 * grid.half_x()}) {  // k = (1, 0), (3, 0) and (2, 2) times 2 pi / 8
        double kx, ky;
        ASSERT_TRUE(slab_wave_vector(grid, at, length, length, kx, ky));
        const double k2 = kx * kx + ky * ky, kappa = std::sqrt(k2);
        double size = 0.0;
        for (int n : {0, 1, 7, 400, 1999, 2000}) {
            fill(at * grid.nz + n);
            const SlabKernelEntry& entry = table[at * grid.nz + n];
            const double out[4] = {entry.tt, entry.ll, entry.zz, entry.lz};
            const double s = n * hz;
            const int panels = 4 * n + 400;
            const double reference[4] = {
                gauss_legendre([&](double q) { return std::cos(q * s) / (k2 + q * q); }, band, panels),
                gauss_legendre([&](double q) { return std::cos(q * s) * q * q / ((k2 + q * q) * (k2 + q * q)); }, band,
                               panels),
                gauss_legendre([&](double q) { return std::cos(q * s) * k2 / ((k2 + q * q) * (k2 + q * q)); }, band,
                               panels),
                gauss_legendre([&](double q) { return kappa * q * std::sin(q * s) / ((k2 + q * q) * (k2 + q * q)); },
                               band, panels)};
            if (n == 0) size = std::max({reference[0], reference[1], reference[2]});
            for (int c = 0; c < 4; ++c) {
                const double error = std::fabs(out[c] - reference[c]) / size;
                worst = std::max(worst, error);
                EXPECT_LT(error, 1e-6) << "wave vector " << at << ", n = " << n << ", kernel " << c;
            }
        }
    }
    std::printf("largest error of the table at nz = 2001: %.2e of the kernel at s = 0\n", worst);
}

// The velocity spectrum of the slit for a random force spectrum, in precision R.
template <class R>
std::vector<std::complex<double>> slit_velocity(const FftGrid& grid, double length, double hz,
                                                const std::vector<std::complex<double>>& force) {
    const std::vector<SlabKernelEntry> table = kernel_table(grid, length, length, hz);
    std::vector<Complex<R>> f(force.size()), u(force.size());
    for (size_t i = 0; i < force.size(); ++i) f[i] = {R(force[i].real()), R(force[i].imag())};
    const int64_t plane = int64_t(grid.half_x()) * grid.ny;
    const SlabStokesSolve<R> solve{f.data(), u.data(), table.data(), grid, length, length, hz, hz, SlabWalls::slit};
    for (int64_t at = 0; at < plane; ++at) solve(at, Lanes{});
    std::vector<std::complex<double>> out(u.size());
    for (size_t i = 0; i < u.size(); ++i) out[i] = {double(u[i].re), double(u[i].im)};
    return out;
}

TEST(SlabStokesSolve, SinglePrecisionKeepsTheWallsOfAThinSlit) {
    // H = 1 in a plane 2000 wide: kappa H from 3e-3, where the slit's 4 x 4 system is nearly singular.
    const FftGrid grid{4, 4, 9};
    const double length = 2000.0, hz = 0.125;
    std::mt19937 engine(11);
    std::normal_distribution<double> normal;
    std::vector<std::complex<double>> force(3 * grid.spectrum_points());
    for (auto& f : force) f = {normal(engine), normal(engine)};
    const auto single = slit_velocity<float>(grid, length, hz, force);
    const auto exact = slit_velocity<double>(grid, length, hz, force);
    // The wave vectors k != 0 only (k = 0 has no wall solution), each against its own size.
    const int64_t plane = int64_t(grid.half_x()) * grid.ny, component = plane * grid.nz;
    double worst = 0.0;
    for (int64_t at = 1; at < plane; ++at) {
        double size = 0.0, error = 0.0;
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < grid.nz; ++i) {
                const int64_t node = at + i * plane + c * component;
                size = std::max(size, std::abs(exact[node]));
                error = std::max(error, std::abs(single[node] - exact[node]));
            }
        if (size > 0.0) worst = std::max(worst, error / size);
    }
    std::printf("single against double, slit of kappa H >= 3e-3: %.2e\n", worst);
    EXPECT_LT(worst, 1e-5);
}

TEST(SlabAxisZ, SlitWeightsAreContinuousAcrossTheMidplaneAndVanishOnTheWalls) {
    // A slit 2 a high (the thinnest allowed), a = 1, spacing sigma / 2.
    const double radius = 1.0, height = 2.0;
    const int sizes[3] = {16, 16, 15};
    const double box[2] = {4.0, 4.0};
    const SlabPlan plan = make_slab_plan(sizes, box, height, radius, SlabWalls::slit, 1e-8);
    EXPECT_EQ(plan.images, 2);  // the images through either wall and the copies 2H away reach the slab
    const SlabAxisZ<double> z{-0.5 * height, height / (sizes[2] - 1), sizes[2], sizes[2],
                              0.5 / (plan.sigma * plan.sigma), 1.0 / std::sqrt(2.0 * M_PI * plan.sigma * plan.sigma),
                              SlabWalls::slit, plan.images};
    const double eps = 1e-7;
    double jump = 0.0, size = 0.0, wall = 0.0, mirror = 0.0;
    for (int node = 0; node < sizes[2]; ++node) {
        jump = std::max(jump, std::fabs(z.weight(node, eps) - z.weight(node, -eps)));
        size = std::max(size, std::fabs(z.weight(node, 0.0)));
        mirror = std::max(mirror, std::fabs(z.weight(node, 0.3) - z.weight(sizes[2] - 1 - node, -0.3)));
    }
    for (double at : {-0.9, -0.2, 0.0, 0.5})
        wall = std::max({wall, std::fabs(z.weight(0, at)), std::fabs(z.weight(sizes[2] - 1, at))});
    std::printf("weights across z = 0: jump %.2e, at the walls %.2e, of %.2e\n", jump, wall, size);
    EXPECT_LT(jump, 1e-5 * size);
    EXPECT_LT(wall, plan.cut * size);  // the images beyond the Gaussian's reach are left out
    EXPECT_LT(mirror, 1e-12 * size);
}

// The `support` nodes of n (at origin + p h, periodic with period n h or not) closest to `at`, and
// their distances from it, by sorting all of them.
std::vector<std::pair<int, double>> closest_nodes(double at, double origin, double h, int n, bool periodic, int support) {
    std::vector<std::pair<double, int>> byDistance;
    for (int p = 0; p < n; ++p) {
        double d = origin + p * h - at;
        if (periodic) d -= n * h * std::round(d / (n * h));
        byDistance.push_back({std::fabs(d), p});
    }
    std::sort(byDistance.begin(), byDistance.end());
    std::vector<std::pair<int, double>> nodes;
    for (int k = 0; k < support; ++k) nodes.push_back({byDistance[k].second, byDistance[k].first});
    return nodes;
}

TEST(SlabSpreading, TabulatedWeightsSpreadAndAverageAsTheDirectSum) {
    // A slit 6 a high, spacing a/2 (0.4 a along z), the Gaussian cut at 1e-3: 10 x 10 x 12 points of
    // 16 x 14 x 16.
    const CpuBackend backend{1};
    const int sizes[3] = {16, 14, 16};
    const double box[2] = {8.0, 7.0}, height = 6.0;
    const SlabPlan plan = make_slab_plan(sizes, box, height, 1.0, SlabWalls::slit, 1e-3);
    ASSERT_EQ(plan.support, 10);
    ASSERT_EQ(plan.supportZ, 12);
    const SlabAxes<double> axes = slab_axes<double>(plan);
    // Across the seams of x and y, near either wall, inside; the last is outside the group.
    const std::vector<Real4<double>> pos = {
        {3.9, 0.1, 0.3, 0}, {-3.95, -3.4, -2.8, 0}, {0.3, 3.3, 2.9, 0}, {1.1, -1.7, 0.05, 0}, {0.2, 0.4, 0.6, 0}};
    const std::vector<uint8_t> group = {1, 1, 1, 1, 0};
    const int count = static_cast<int>(pos.size());
    std::mt19937 engine(5);
    std::normal_distribution<double> normal;
    std::vector<double> v(3 * count), field(3 * plan.grid.points());
    for (double& x : v) x = normal(engine);
    for (double& x : field) x = normal(engine);

    // The reference: each member's weight at every node of the support points closest to it.
    const double norm = 1.0 / std::sqrt(2.0 * M_PI * plan.sigma * plan.sigma);
    const auto gaussian = [&](double d) { return norm * std::exp(-d * d / (2.0 * plan.sigma * plan.sigma)); };
    const double hz = height / (sizes[2] - 1), cellVolume = box[0] / sizes[0] * box[1] / sizes[1] * hz;
    const int64_t points = plan.grid.points();
    std::vector<double> density(3 * points, 0.0), average(3 * count, 0.0);
    for (int i = 0; i < count; ++i) {
        if (!group[i]) continue;
        const auto xs = closest_nodes(pos[i].x, -0.5 * box[0], box[0] / sizes[0], sizes[0], true, plan.support);
        const auto ys = closest_nodes(pos[i].y, -0.5 * box[1], box[1] / sizes[1], sizes[1], true, plan.support);
        const auto zs = closest_nodes(pos[i].z, -0.5 * height, hz, sizes[2], false, plan.supportZ);
        for (const auto& [z, dz] : zs)
            for (const auto& [y, dy] : ys)
                for (const auto& [x, dx] : xs) {
                    const double w = gaussian(dx) * gaussian(dy) * axes.z.weight(z, pos[i].z);
                    const int64_t at = plan.grid.index(x, y, z);
                    for (int c = 0; c < 3; ++c) {
                        density[at + c * points] += w * v[3 * i + c];
                        average[3 * i + c] += cellVolume * w * field[at + c * points];
                    }
                }
    }

    std::vector<int> first(3 * count);
    std::vector<double> weights(size_t(2 * plan.support + plan.supportZ) * count);
    const SlabWeighParticle<double, SlabAxisZ<double>> weigh{pos.data(), group.data(), axes, first.data(), weights.data()};
    for (int i = 0; i < count; ++i) weigh(i);
    LineBins<CpuBackend> bins(backend, sizes[1] * sizes[2]);
    bins.sort(count, SlabKernelLine{group.data(), first.data(), sizes[1]});
    const SlabWeights<double> table{first.data(), weights.data(), plan.support, plan.supportZ};
    std::vector<double> spread(3 * points, -1.0), averaged(3 * count, -1.0);
    const SlabSpreadLine<double, FlatVectors<double>> spreadLine{{v.data()}, bins.order(), bins.line_start(), table,
                                                                 plan.grid, spread.data()};
    for (int line = 0; line < sizes[1] * sizes[2]; ++line) spreadLine(line, Lanes{});
    const SlabInterpolate<double> interpolate{group.data(), table, plan.grid, field.data(), cellVolume, averaged.data()};
    for (int i = 0; i < count; ++i) interpolate(i, Lanes{});

    double size = 0.0, error = 0.0;
    for (int64_t k = 0; k < 3 * points; ++k) {
        size = std::max(size, std::fabs(density[k]));
        error = std::max(error, std::fabs(spread[k] - density[k]));
    }
    EXPECT_LT(error, 1e-13 * size) << "spreading, of " << size;
    for (int k = 0; k < 3 * count; ++k) EXPECT_NEAR(averaged[k], average[k], 1e-13 * size * cellVolume) << "average " << k;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(averaged[3 * (count - 1) + c], 0.0) << "outside the group";
}

TEST(CpuFft3d, BatchedPlaneTransformsAreThePlanesTransforms) {
    const CpuBackend backend{1};
    const FftGrid planes{6, 5, 4};
    std::mt19937 engine(3);
    std::normal_distribution<double> normal;
    std::vector<double> real(planes.points()), back(planes.points());
    for (double& v : real) v = normal(engine);
    std::vector<Complex<double>> batched(planes.spectrum_points()), one(planes.spectrum_points());
    CpuFft3d<double>(backend, planes, FftAxes::xy).forward(real.data(), batched.data());
    const FftGrid plane{planes.nx, planes.ny, 1};
    const CpuFft3d<double> single(backend, plane);
    for (int z = 0; z < planes.nz; ++z)
        single.forward(real.data() + z * plane.points(), one.data() + z * plane.spectrum_points());
    for (size_t i = 0; i < one.size(); ++i) {
        EXPECT_NEAR(batched[i].re, one[i].re, 1e-12);
        EXPECT_NEAR(batched[i].im, one[i].im, 1e-12);
    }
    CpuFft3d<double>(backend, planes, FftAxes::xy).inverse(batched.data(), back.data());
    for (size_t i = 0; i < real.size(); ++i) EXPECT_NEAR(back[i], plane.points() * real[i], 1e-11);
}

}  // namespace
}  // namespace structmd
