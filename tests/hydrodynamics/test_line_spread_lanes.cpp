// The spreads that give each grid line along x to one item of several lanes, Gaussian (FCM and PSE's
// far field) and planar (Quasi2D) (core/lanes.hpp's owns_point: a lane clears and sums the points x
// with x modulo the lane count equal to its rank): for every power-of-two lane count up to a warp,
// running each line's lanes one rank after the other on the host gives the grid of one lane bit for
// bit. A point no lane clears keeps the sentinel the grid starts with, a point two lanes own takes
// its terms twice, and a lane that clears after another summed loses those terms; the lanes run in
// both rank orders, so either way round shows. The GPU runs the same functors with the lanes side by
// side; the CPU backend runs them with one lane.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "core/lanes.hpp"
#include "hydrodynamics/fcm_mesh.hpp"
#include "hydrodynamics/gaussian_spreading.hpp"
#include "hydrodynamics/planar_mesh.hpp"
#include "neighbour/line_bins.hpp"

namespace structmd {
namespace {

constexpr int kWarpLanes = 32;

// count particles in the box [-L/2, L/2) of sides `box`, with vectors (forces) of mixed signs and
// sizes, so that a term added twice or lost shows in every bit.
template <class R>
struct SpreadInputs {
    HostBuffer<Real4<R>> pos, vectors;

    SpreadInputs(const CpuBackend& backend, int count, const double box[3], unsigned seed) {
        std::mt19937 engine(seed);
        std::uniform_real_distribution<double> unit(-0.5, 0.5), value(-2.0, 2.0);
        std::vector<Real4<R>> p(count), v(count);
        for (int i = 0; i < count; ++i) {
            // A few on the box's lower faces, whose kernels wrap around every periodic axis.
            const double x = i % 7 == 0 ? -0.5 : unit(engine), y = unit(engine);
            const double z = i % 5 == 0 ? -0.5 : unit(engine);
            p[i] = {R(x * box[0]), R(y * box[1]), R(z * box[2]), R(0)};
            v[i] = {R(value(engine)), R(value(engine)), R(value(engine)), R(0)};
        }
        backend.upload(pos, p.data(), p.size());
        backend.upload(vectors, v.data(), v.size());
    }
};

// The grid after spread(line, lanes) for every line and every rank of `count` lanes, ranks in
// ascending or descending order, on a grid that starts as `initial`.
template <class R, class Spread>
std::vector<R> spread_by_lanes(const Spread& spread, int64_t lines, int count, bool descending, R* grid,
                               const std::vector<R>& initial) {
    std::copy(initial.begin(), initial.end(), grid);
    for (int64_t line = 0; line < lines; ++line)
        for (int rank = 0; rank < count; ++rank) {
            Lanes lanes;
            lanes.count = count;
            lanes.lane = descending ? count - 1 - rank : rank;
            spread(line, lanes);
        }
    return std::vector<R>(grid, grid + initial.size());
}

// spread on 2, 4, ..., 32 lanes, in both rank orders, gives the grid of one lane bit for bit; and
// that grid holds terms on at least a quarter of its points, so that the comparison means something.
template <class R, class Spread>
void expect_same_on_every_lane_count(const Spread& spread, int64_t lines, R* grid, const std::vector<R>& initial) {
    const std::vector<R> one = spread_by_lanes(spread, lines, 1, false, grid, initial);
    size_t termed = 0;
    for (size_t k = 0; k < one.size(); ++k) termed += one[k] != initial[k] && one[k] != R(0);
    EXPECT_GT(4 * termed, one.size()) << "too few points took terms: " << termed << " of " << one.size();
    for (int count = 2; count <= kWarpLanes; count *= 2)
        for (bool descending : {false, true}) {
            SCOPED_TRACE(std::to_string(count) + " lanes, ranks " + (descending ? "descending" : "ascending"));
            const std::vector<R> lanes = spread_by_lanes(spread, lines, count, descending, grid, initial);
            size_t differ = 0, first = one.size();
            for (size_t k = 0; k < one.size(); ++k)
                if (std::memcmp(&one[k], &lanes[k], sizeof(R)) != 0) {
                    if (differ++ == 0) first = k;
                }
            EXPECT_EQ(differ, 0u) << "first at grid index " << first << ": "
                                  << (first < one.size() ? lanes[first] : R(0)) << " against one lane's "
                                  << (first < one.size() ? one[first] : R(0));
        }
}

// A grid that starts far from anything the spreads write: a point left uncleared keeps it.
template <class R>
std::vector<R> sentinel_grid(int64_t size) {
    return std::vector<R>(static_cast<size_t>(size), R(1e30));
}

template <class R>
void check_gaussian() {
    CpuBackend backend{1};
    FcmPlan plan;
    plan.grid = FftGrid{20, 12, 10};  // 20 points a line: 32 lanes leave 12 with none
    plan.box[0] = 10.0;
    plan.box[1] = 6.0;
    plan.box[2] = 5.0;
    plan.sigma = 0.6;
    plan.support = 7;
    const FcmAxes<R> axes = fcm_axes<R>(plan);
    SpreadInputs<R> p(backend, 60, plan.box, 11);
    const int lines = plan.grid.ny * plan.grid.nz;
    LineBins<CpuBackend> bins(backend, lines);
    bins.sort(60, GaussianKernelLine<R, FcmAxis<R>>{p.pos.data(), nullptr, axes});
    HostBuffer<R> density;
    backend.resize(density, 3 * plan.grid.points());
    const GaussianSpreadLine<R, FcmAxis<R>, Real4Vectors<R>> spread{
        p.pos.data(), {p.vectors.data()}, bins.order(), bins.line_start(), axes, density.data()};
    expect_same_on_every_lane_count(spread, lines, density.data(), sentinel_grid<R>(3 * plan.grid.points()));
}

template <class R>
void check_planar(bool withNumberDensity) {
    CpuBackend backend{1};
    PlanarPlan plan;
    plan.grid = FftGrid{36, 16, 1};
    plan.box[0] = 18.0;
    plan.box[1] = 8.0;
    plan.sigma = 0.7;
    plan.support = 9;
    const PlanarAxes<R> axes = planar_axes<R>(plan);
    const double box[3] = {plan.box[0], plan.box[1], 1.0};
    SpreadInputs<R> p(backend, 50, box, 12);
    LineBins<CpuBackend> bins(backend, plan.grid.ny);
    bins.sort(50, PlanarKernelLine<R>{p.pos.data(), nullptr, axes});
    HostBuffer<R> density;
    backend.resize(density, 3 * plan.grid.points());
    const PlanarSpreadLine<R> spread{
        p.pos.data(), p.vectors.data(), bins.order(), bins.line_start(), axes, density.data(), withNumberDensity};
    expect_same_on_every_lane_count(spread, plan.grid.ny, density.data(), sentinel_grid<R>(3 * plan.grid.points()));
}

TEST(LineSpreadLanes, GaussianSpreadLineIsTheSameOnEveryLaneCount) {
    check_gaussian<float>();
    check_gaussian<double>();
}

TEST(LineSpreadLanes, PlanarSpreadLineIsTheSameOnEveryLaneCount) {
    for (bool withNumberDensity : {false, true}) {
        SCOPED_TRACE(withNumberDensity ? "with the number density" : "forces alone");
        check_planar<float>(withNumberDensity);
        check_planar<double>(withNumberDensity);
    }
}

}  // namespace
}  // namespace structmd
