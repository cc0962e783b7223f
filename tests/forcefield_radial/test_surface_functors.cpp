// The Surface family (flat_surfaces.hpp, plain_cylinder.hpp): energies against the formulas of the
// input specification, written out here independently of the functors; forces against a central
// finite difference of the functor's energy in x, y and z, on both sides of each wall and in every
// region of the plain cylinder; the cutoffs, where the energy must reach zero; and single precision
// against double.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "core/dual.hpp"
#include "forcefield/flat_surfaces.hpp"
#include "forcefield/plain_cylinder.hpp"
#include "forcefield/wca_polyhedron.hpp"

using namespace structmd;

namespace {

constexpr double kEnergyTolerance = 1e-10;          // relative, double against the formula
constexpr double kForceTolerance = 1e-6;            // relative to |F|, against the central difference
constexpr double kSinglePrecisionTolerance = 1e-4;  // relative, float against double

struct WorstErrors {
    double energy = 0.0;
    double force = 0.0;
    double single_precision = 0.0;
    int points = 0;
};
WorstErrors worst;

class PrintWorstErrors : public ::testing::Environment {
public:
    void TearDown() override {
        std::printf("%d points; worst relative errors: energy %.3g, force %.3g, float against double %.3g\n",
                    worst.points, worst.energy, worst.force, worst.single_precision);
    }
};
::testing::Environment* const print_worst_errors = ::testing::AddGlobalTestEnvironment(new PrintWorstErrors);

double norm(Vec3<double> v) { return std::sqrt(dot(v, v)); }

std::string describe(Vec3<double> r) {
    return "r = (" + std::to_string(r.x) + ", " + std::to_string(r.y) + ", " + std::to_string(r.z) + ")";
}

template <class Surface>
double energy_at(Vec3<double> r, const typename Surface::template Params<double>& p) {
    Vec3<double> ignored;
    return Surface::compute(r, 0.5, p, 0.0, ignored);
}

// The energy equals the given value (both zero, or within kEnergyTolerance) and the force minus the
// central difference of the energy along each axis.
template <class Surface>
void expect_energy_and_force(Vec3<double> r, const typename Surface::template Params<double>& p,
                             double expected_energy) {
    SCOPED_TRACE(describe(r));
    ++worst.points;
    Vec3<double> force;
    const double energy = Surface::compute(r, 0.5, p, 0.0, force);
    const double energy_error =
        expected_energy == 0.0 ? std::fabs(energy) : std::fabs(energy - expected_energy) / std::fabs(expected_energy);
    EXPECT_LT(energy_error, kEnergyTolerance) << energy << " against " << expected_energy;
    const double h = 1e-6;
    const auto minus_slope = [&](Vec3<double> axis) {
        return -(energy_at<Surface>(r + h * axis, p) - energy_at<Surface>(r - h * axis, p)) / (2.0 * h);
    };
    const Vec3<double> numeric{minus_slope({1, 0, 0}), minus_slope({0, 1, 0}), minus_slope({0, 0, 1})};
    const double scale = std::max(norm(numeric), 1e-3);
    const double force_error = norm(force - numeric) / scale;
    EXPECT_LT(force_error, kForceTolerance)
        << "force (" << force.x << ", " << force.y << ", " << force.z << ") against (" << numeric.x << ", " << numeric.y
        << ", " << numeric.z << ")";
    worst.energy = std::max(worst.energy, energy_error);
    worst.force = std::max(worst.force, force_error);
}

template <class Surface, class Make>
void expect_float_matches_double(Make make, Vec3<double> r) {
    SCOPED_TRACE(describe(r));
    const auto pd = make(double{});
    const auto pf = make(float{});
    Vec3<double> fd;
    Vec3<float> ff;
    const double ed = Surface::compute(r, 0.5, pd, 0.0, fd);
    const float ef = Surface::compute(Vec3<float>{float(r.x), float(r.y), float(r.z)}, 0.5f, pf, 0.0f, ff);
    ASSERT_GT(std::fabs(ed), 0.0) << "the point must feel the surface";
    const double energy_error = std::fabs(ef - ed) / std::fabs(ed);
    const double force_error = norm(Vec3<double>{ff.x - fd.x, ff.y - fd.y, ff.z - fd.z}) / norm(fd);
    EXPECT_LT(energy_error, kSinglePrecisionTolerance);
    EXPECT_LT(force_error, kSinglePrecisionTolerance);
    worst.single_precision = std::max({worst.single_precision, energy_error, force_error});
}

// ---- flat surfaces ---------------------------------------------------------------------------------

constexpr double kSurface = -1.5;  // z_s
constexpr double kSigma = 0.9;

double lj1(double eps, double sigma, double d) {
    const double s6 = std::pow(sigma / std::fabs(d), 6);
    return 4.0 * eps * (s6 * s6 - s6);
}
double lj2(double eps, double sigma, double d) {
    const double s6 = std::pow(sigma / std::fabs(d), 6);
    return eps * (s6 * s6 - 2.0 * s6);
}
double wca1(double eps, double sigma, double d) {
    return std::fabs(d) < std::pow(2.0, 1.0 / 6.0) * sigma ? lj1(eps, sigma, d) + eps : 0.0;
}
double wca2(double eps, double sigma, double d) { return std::fabs(d) < sigma ? lj2(eps, sigma, d) + eps : 0.0; }
double integrated(double eps, double sigma, double d) {
    const double s3 = std::pow(sigma / std::fabs(d), 3);
    return eps * (s3 * s3 * s3 - 2.0 * s3);
}

// Points at distances |d| in [0.75 sigma, 3 sigma] from the wall, on both sides, at random x and y.
template <class Surface>
void check_flat_surface(double eps, const std::function<double(double)>& formula, double far = 3.0) {
    const auto p = Surface::template make_params<double>(kSurface, eps, kSigma);
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> lateral(-20.0, 20.0), distance(0.75 * kSigma, far * kSigma);
    for (int k = 0; k < 40; ++k) {
        const double d = (k % 2 ? 1.0 : -1.0) * distance(rng);
        const Vec3<double> r{lateral(rng), lateral(rng), kSurface + d};
        expect_energy_and_force<Surface>(r, p, formula(d));
        Vec3<double> force;
        Surface::compute(r, 0.5, p, 0.0, force);
        EXPECT_EQ(force.x, 0.0);
        EXPECT_EQ(force.y, 0.0);
    }
}

TEST(SurfaceLennardJones, Type1IsTheTwelveSixPotentialOfTheDistanceToTheWall) {
    for (const double eps : {1.0, 0.4})
        check_flat_surface<SurfaceLennardJonesType1>(eps, [eps](double d) { return lj1(eps, kSigma, d); });
}

TEST(SurfaceLennardJones, Type2HasItsMinusEpsMinimumAtSigma) {
    for (const double eps : {1.0, 0.4})
        check_flat_surface<SurfaceLennardJonesType2>(eps, [eps](double d) { return lj2(eps, kSigma, d); });
    const auto p = SurfaceLennardJonesType2::make_params<double>(kSurface, 0.4, kSigma);
    EXPECT_NEAR(energy_at<SurfaceLennardJonesType2>({0.0, 0.0, kSurface + kSigma}, p), -0.4, 1e-14);
    EXPECT_NEAR(energy_at<SurfaceLennardJonesType2>({0.0, 0.0, kSurface - kSigma}, p), -0.4, 1e-14);
}

TEST(SurfaceWCA, BothTypesAreRepulsiveAndReachZeroAtTheirMinimum) {
    check_flat_surface<SurfaceWCAType1>(1.3, [](double d) { return wca1(1.3, kSigma, d); });
    check_flat_surface<SurfaceWCAType2>(1.3, [](double d) { return wca2(1.3, kSigma, d); });
    const auto p1 = SurfaceWCAType1::make_params<double>(kSurface, 1.3, kSigma);
    const auto p2 = SurfaceWCAType2::make_params<double>(kSurface, 1.3, kSigma);
    const double r1 = std::pow(2.0, 1.0 / 6.0) * kSigma;
    for (const double side : {-1.0, 1.0}) {
        // Just inside the cutoff the energy is O(delta^2) and the force O(delta); beyond it both are 0.
        EXPECT_LT(energy_at<SurfaceWCAType1>({0.0, 0.0, kSurface + side * (r1 - 1e-6)}, p1), 1e-9);
        EXPECT_EQ(energy_at<SurfaceWCAType1>({0.0, 0.0, kSurface + side * (r1 + 1e-9)}, p1), 0.0);
        EXPECT_LT(energy_at<SurfaceWCAType2>({0.0, 0.0, kSurface + side * (kSigma - 1e-6)}, p2), 1e-9);
        EXPECT_EQ(energy_at<SurfaceWCAType2>({0.0, 0.0, kSurface + side * (kSigma + 1e-9)}, p2), 0.0);
        Vec3<double> force;
        SurfaceWCAType1::compute({0.0, 0.0, kSurface + side * 0.95 * kSigma}, 0.5, p1, 0.0, force);
        EXPECT_GT(side * force.z, 0.0) << "pushes away from the wall";
    }
}

TEST(SurfaceGeneralLennardJones, IsWCAForPositiveEpsilonAndTheFullPotentialOfItsMagnitudeForNegative) {
    check_flat_surface<SurfaceGeneralLennardJonesType1>(0.8, [](double d) { return wca1(0.8, kSigma, d); });
    check_flat_surface<SurfaceGeneralLennardJonesType1>(-0.8, [](double d) { return lj1(0.8, kSigma, d); });
    check_flat_surface<SurfaceGeneralLennardJonesType2>(0.8, [](double d) { return wca2(0.8, kSigma, d); });
    check_flat_surface<SurfaceGeneralLennardJonesType2>(-0.8, [](double d) { return lj2(0.8, kSigma, d); });
    // eps = 0 is the (vanishing) WCA form, not an attraction.
    const auto zero = SurfaceGeneralLennardJonesType2::make_params<double>(kSurface, 0.0, kSigma);
    EXPECT_EQ(energy_at<SurfaceGeneralLennardJonesType2>({0.0, 0.0, kSurface + 2.0}, zero), 0.0);
}

TEST(SurfaceIntegratedLennardJones, Type2IsTheNineThreeWallOfTheReference) {
    for (const double eps : {1.0, 0.4})
        check_flat_surface<SurfaceIntegratedLennardJonesType2>(eps,
                                                               [eps](double d) { return integrated(eps, kSigma, d); });
    // Minimum at (3/2)^(1/6) sigma with value -(4/3) sqrt(2/3) eps, zero force there.
    const auto p = SurfaceIntegratedLennardJonesType2::make_params<double>(kSurface, 0.4, kSigma);
    const Vec3<double> at_minimum{0.0, 0.0, kSurface + std::pow(1.5, 1.0 / 6.0) * kSigma};
    Vec3<double> force;
    const double energy = SurfaceIntegratedLennardJonesType2::compute(at_minimum, 0.5, p, 0.0, force);
    EXPECT_NEAR(energy, -0.4 * 4.0 / 3.0 * std::sqrt(2.0 / 3.0), 1e-14);
    EXPECT_NEAR(force.z, 0.0, 1e-13);
}

TEST(SurfaceAnchorage, IsAHarmonicWellOfHalfWidthSigma) {
    const double eps = 2.5;
    const auto p = SurfaceAnchorage::make_params<double>(
        [&] {
            ParameterValues v;
            v.set("surfacePosition", {kSurface});
            v.set("epsilon", {eps});
            v.set("sigma", {kSigma});
            return v;
        }(),
        Constants{});
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> lateral(-20.0, 20.0), inside(-0.98 * kSigma, 0.98 * kSigma),
        outside(1.02 * kSigma, 4.0 * kSigma);
    for (int k = 0; k < 20; ++k) {
        const double d = inside(rng);
        expect_energy_and_force<SurfaceAnchorage>({lateral(rng), lateral(rng), kSurface + d}, p,
                                                  0.5 * eps * (d * d / (kSigma * kSigma) - 1.0));
        const double far = (k % 2 ? 1.0 : -1.0) * outside(rng);
        expect_energy_and_force<SurfaceAnchorage>({lateral(rng), lateral(rng), kSurface + far}, p, 0.0);
    }
    EXPECT_NEAR(energy_at<SurfaceAnchorage>({0.0, 0.0, kSurface}, p), -0.5 * eps, 1e-15);
    // The energy is continuous at the edges of the well.
    EXPECT_NEAR(energy_at<SurfaceAnchorage>({0.0, 0.0, kSurface + kSigma * (1.0 - 1e-9)}, p), 0.0, 1e-8);
}

TEST(ParabolaSurface, PullsParticlesBelowTheWallBackAndLeavesThoseAboveAlone) {
    const double eps = 7.0;
    ParameterValues v;
    v.set("surfacePosition", {kSurface});
    v.set("epsilon", {eps});
    const auto p = ParabolaSurface::make_params<double>(v, Constants{});
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> lateral(-20.0, 20.0), depth(0.01, 3.0);
    for (int k = 0; k < 20; ++k) {
        const double below = depth(rng);
        expect_energy_and_force<ParabolaSurface>({lateral(rng), lateral(rng), kSurface - below}, p,
                                                 0.5 * eps * below * below);
        expect_energy_and_force<ParabolaSurface>({lateral(rng), lateral(rng), kSurface + depth(rng)}, p, 0.0);
    }
    Vec3<double> force;
    ParabolaSurface::compute({0.0, 0.0, kSurface - 0.5}, 0.5, p, 0.0, force);
    EXPECT_DOUBLE_EQ(force.z, 3.5);
}

// ---- plain cylinder --------------------------------------------------------------------------------

constexpr double kPlane = 0.7;   // z0
constexpr double kRadius = 2.0;  // R
constexpr double kCylinderEpsilon = 1.2;
constexpr double kCylinderSigma = 0.8;

// The distance from r to the surface of the solid {z < z0, rho > R}, as the smaller of the distances
// to its two faces: the annulus {z = z0, rho >= R} and the wall {rho = R, z <= z0}. Only meaningful
// outside the solid.
double distance_to_solid(Vec3<double> r) {
    const double rho = std::hypot(r.x, r.y);
    const double dz = r.z - kPlane;
    const double to_annulus = rho >= kRadius ? std::fabs(dz) : std::hypot(kRadius - rho, dz);
    const double to_wall = r.z <= kPlane ? std::fabs(rho - kRadius) : std::hypot(rho - kRadius, dz);
    return std::min(to_annulus, to_wall);
}

double cylinder_energy(Vec3<double> r) {
    const bool solid = r.z < kPlane && std::hypot(r.x, r.y) >= kRadius;
    return solid ? 0.0 : wca1(kCylinderEpsilon, kCylinderSigma, distance_to_solid(r));
}

WCAPlainCylinder::Params<double> cylinder() {
    return WCAPlainCylinder::make_params<double>(kPlane, kRadius, kCylinderEpsilon, kCylinderSigma);
}

// A point at cylindrical coordinates (rho, phi, z).
Vec3<double> cylindrical(double rho, double phi, double z) { return {rho * std::cos(phi), rho * std::sin(phi), z}; }

TEST(WCAPlainCylinder, EnergyIsTheWCAOfTheDistanceToTheSolidInEveryRegion) {
    const auto p = cylinder();
    std::mt19937 rng(44);
    std::uniform_real_distribution<double> angle(0.0, 6.283185307179586), gap(0.7, 0.89);
    for (int k = 0; k < 30; ++k) {
        const double phi = angle(rng);
        const double g = gap(rng) * kCylinderSigma * 1.1;  // within the WCA range 2^(1/6) sigma
        // Above the plane beyond the well's mouth: the plane acts.
        const Vec3<double> plane = cylindrical(kRadius + 0.1 + 2.0 * gap(rng), phi, kPlane + g);
        // In the well, below the plane: its wall acts.
        const Vec3<double> wall = cylindrical(kRadius - g, phi, kPlane - 0.2 - 3.0 * gap(rng));
        // Above the mouth: the rim acts, at distance g in a direction between the axis and the plane.
        const double tilt = 0.2 + 1.2 * gap(rng);
        const Vec3<double> rim = cylindrical(kRadius - g * std::cos(tilt), phi, kPlane + g * std::sin(tilt));
        for (const Vec3<double>& r : {plane, wall, rim}) {
            ASSERT_NEAR(distance_to_solid(r), g, 1e-12) << describe(r);
            expect_energy_and_force<WCAPlainCylinder>(r, p, cylinder_energy(r));
            ASSERT_GT(cylinder_energy(r), 0.0);
        }
        // Beyond the range of the WCA potential, in each region, and inside the solid: nothing.
        for (const Vec3<double>& r :
             {cylindrical(kRadius + 1.0, phi, kPlane + 1.0), cylindrical(kRadius - 1.0, phi, kPlane - 5.0),
              cylindrical(kRadius - 0.8, phi, kPlane + 0.8), cylindrical(kRadius + 0.3, phi, kPlane - 0.3)})
            expect_energy_and_force<WCAPlainCylinder>(r, p, 0.0);
    }
}

TEST(WCAPlainCylinder, EnergyIsContinuousAcrossTheRegions) {
    const auto p = cylinder();
    const double e = 1e-9;
    const double g = 0.75;
    // Across rho = R above the plane (plane <-> rim), and across z = z0 inside the well (wall <-> rim).
    const double across_rho = energy_at<WCAPlainCylinder>(cylindrical(kRadius + e, 0.3, kPlane + g), p);
    const double before_rho = energy_at<WCAPlainCylinder>(cylindrical(kRadius - e, 0.3, kPlane + g), p);
    EXPECT_NEAR(across_rho, before_rho, 1e-6 * across_rho);
    const double across_z = energy_at<WCAPlainCylinder>(cylindrical(kRadius - g, 1.1, kPlane + e), p);
    const double before_z = energy_at<WCAPlainCylinder>(cylindrical(kRadius - g, 1.1, kPlane - e), p);
    EXPECT_NEAR(across_z, before_z, 1e-6 * across_z);
    EXPECT_NEAR(across_z, wca1(kCylinderEpsilon, kCylinderSigma, g), 1e-6);
}

TEST(WCAPlainCylinder, OnTheAxisTheForceIsAlongZOnly) {
    // A narrow well (R < 2^(1/6) sigma): on its axis the whole rim, or the whole wall, is equally near.
    const auto p = WCAPlainCylinder::make_params<double>(kPlane, 0.85, kCylinderEpsilon, kCylinderSigma);
    for (const double z : {kPlane - 2.0, kPlane + 0.3}) {
        Vec3<double> force;
        const double energy = WCAPlainCylinder::compute({0.0, 0.0, z}, 0.5, p, 0.0, force);
        const double g = z < kPlane ? 0.85 : std::hypot(0.85, z - kPlane);
        EXPECT_NEAR(energy, wca1(kCylinderEpsilon, kCylinderSigma, g), 1e-12);
        EXPECT_TRUE(std::isfinite(force.z));
        EXPECT_EQ(force.x, 0.0);
        EXPECT_EQ(force.y, 0.0);
    }
    // Without a well (R = 0), as in the reference's test input, the axis above the plane sees the plane.
    const auto flat = WCAPlainCylinder::make_params<double>(kPlane, 0.0, kCylinderEpsilon, kCylinderSigma);
    expect_energy_and_force<WCAPlainCylinder>({0.0, 0.0, kPlane + 0.8}, flat,
                                              wca1(kCylinderEpsilon, kCylinderSigma, 0.8));
}

// ---- polyhedron -----------------------------------------------------------------------------------

// A cube of half-edge 1.5 centred on c, as 12 triangles (each square face split along a diagonal, the
// two halves wound either way: the order of a face's vertices must not matter).
constexpr double kHalfEdge = 1.5;
const Vec3<double> kCubeCentre{0.3, -0.2, 0.1};
constexpr double kCubeEpsilon = 0.9;
constexpr double kCubeSigma = 0.7;

struct Mesh {
    std::vector<Vec3<double>> vertices;
    std::vector<int> faces;
};

const Mesh& cube() {
    static const Mesh mesh = [] {
        Mesh m;
        for (int k = 0; k < 8; ++k)
            m.vertices.push_back(kCubeCentre + Vec3<double>{k & 1 ? kHalfEdge : -kHalfEdge,
                                                            k & 2 ? kHalfEdge : -kHalfEdge,
                                                            k & 4 ? kHalfEdge : -kHalfEdge});
        // Each face by its four corners in order around it.
        const int quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
        for (const auto& q : quads) m.faces.insert(m.faces.end(), {q[0], q[1], q[2], q[0], q[3], q[2]});
        return m;
    }();
    return mesh;
}

template <class R>
WCAPolyhedronPotential::Params<R> cube_params(const std::vector<Vec3<R>>& vertices) {
    ParameterValues v;
    v.set("epsilon", {kCubeEpsilon});
    v.set("sigma", {kCubeSigma});
    return WCAPolyhedronPotential::make_params<R>(v, vertices.data(), cube().faces.data(),
                                                  static_cast<int>(cube().faces.size() / 3));
}

template <class R>
std::vector<Vec3<R>> cube_vertices() {
    std::vector<Vec3<R>> out;
    for (const Vec3<double>& x : cube().vertices) out.push_back({R(x.x), R(x.y), R(x.z)});
    return out;
}

// The distance from r to the cube's surface, from the box's own geometry: inside, to the nearest face;
// outside, the length of the part of |r - c| beyond the half-edge along each axis.
double distance_to_cube(Vec3<double> r) {
    const Vec3<double> d = r - kCubeCentre;
    const double q[3] = {std::fabs(d.x) - kHalfEdge, std::fabs(d.y) - kHalfEdge, std::fabs(d.z) - kHalfEdge};
    if (q[0] <= 0.0 && q[1] <= 0.0 && q[2] <= 0.0) return -std::max({q[0], q[1], q[2]});
    double s = 0.0;
    for (double x : q) s += std::max(x, 0.0) * std::max(x, 0.0);
    return std::sqrt(s);
}

TEST(WCAPolyhedron, EnergyIsTheWCAOfTheDistanceToTheMeshInsideAndOutside) {
    const std::vector<Vec3<double>> vertices = cube_vertices<double>();
    const auto p = cube_params<double>(vertices);
    std::mt19937 rng(91);
    std::normal_distribution<double> gaussian;
    std::uniform_real_distribution<double> gap(0.6, 0.78), spread(-1.2, 1.2);
    int acting = 0;
    for (int k = 0; k < 60; ++k) {
        // Near a face from either side, near an edge and near a corner from outside, and far away.
        const int axis = k % 3;
        const double side = k % 2 ? 1.0 : -1.0;
        Vec3<double> d{spread(rng), spread(rng), spread(rng)};
        const double g = gap(rng);
        Vec3<double> r;
        switch (k % 5) {
            case 0:
                (axis == 0 ? d.x : axis == 1 ? d.y : d.z) = side * (kHalfEdge + g);
                r = kCubeCentre + d;
                break;
            case 1:
                (axis == 0 ? d.x : axis == 1 ? d.y : d.z) = side * (kHalfEdge - g);
                r = kCubeCentre + d;
                break;
            case 2: {
                Vec3<double> u{gaussian(rng), gaussian(rng), 0.0};
                u = (g / norm(u)) * Vec3<double>{std::fabs(u.x), std::fabs(u.y), 0.0};
                r = kCubeCentre + Vec3<double>{side * (kHalfEdge + u.x), kHalfEdge + u.y, spread(rng)};
                break;
            }
            case 3: {
                Vec3<double> u{std::fabs(gaussian(rng)), std::fabs(gaussian(rng)), std::fabs(gaussian(rng))};
                r = kCubeCentre + Vec3<double>{kHalfEdge, -kHalfEdge, side * kHalfEdge} +
                    (g / norm(u)) * Vec3<double>{u.x, -u.y, side * u.z};
                break;
            }
            default: r = kCubeCentre + Vec3<double>{4.0 * side, spread(rng), spread(rng)};
        }
        const double expected = distance_to_cube(r) < std::pow(2.0, 1.0 / 6.0) * kCubeSigma
                                    ? wca1(kCubeEpsilon, kCubeSigma, distance_to_cube(r))
                                    : 0.0;
        acting += expected > 0.0;
        expect_energy_and_force<WCAPolyhedronPotential>(r, p, expected);
    }
    EXPECT_GE(acting, 40);
}

TEST(WCAPolyhedron, ForceIsAlongTheFaceNormalEdgeOrCorner) {
    const std::vector<Vec3<double>> vertices = cube_vertices<double>();
    const auto p = cube_params<double>(vertices);
    Vec3<double> force;
    // Above the +z face, beyond the +x+y edge, beyond the +x-y-z corner, and inside near the -x face.
    WCAPolyhedronPotential::compute(kCubeCentre + Vec3<double>{0.2, 0.4, kHalfEdge + 0.7}, 0.5, p, 0.0, force);
    EXPECT_NEAR(force.x, 0.0, 1e-12);
    EXPECT_NEAR(force.y, 0.0, 1e-12);
    EXPECT_GT(force.z, 0.0);
    WCAPolyhedronPotential::compute(kCubeCentre + Vec3<double>{kHalfEdge + 0.5, kHalfEdge + 0.5, 0.3}, 0.5, p, 0.0,
                                    force);
    EXPECT_NEAR(force.x, force.y, 1e-12 * std::fabs(force.x));
    EXPECT_NEAR(force.z, 0.0, 1e-12);
    WCAPolyhedronPotential::compute(kCubeCentre + Vec3<double>{kHalfEdge + 0.4, -kHalfEdge - 0.4, -kHalfEdge - 0.4},
                                    0.5, p, 0.0, force);
    EXPECT_NEAR(force.x, -force.y, 1e-12 * std::fabs(force.x));
    EXPECT_NEAR(force.y, force.z, 1e-12 * std::fabs(force.x));
    WCAPolyhedronPotential::compute(kCubeCentre + Vec3<double>{-kHalfEdge + 0.6, 0.1, 0.2}, 0.5, p, 0.0, force);
    EXPECT_GT(force.x, 0.0) << "pushes inside particles away from the face too";
    EXPECT_NEAR(force.y, 0.0, 1e-12);
}

// Each functor evaluated in dual numbers (core/dual.hpp, what the Hessian measure does) gives the
// derivative of its force: against a central difference of the double force, row by row.
template <class Surface, class Make>
void expect_dual_second_derivatives(Make make, Vec3<double> r) {
    SCOPED_TRACE(describe(r));
    const auto p = make(double{});
    const auto pd = make(Dual<double>{});
    const double h = 1e-6;
    for (int axis = 0; axis < 3; ++axis) {
        Vec3<Dual<double>> rd{Dual<double>(r.x), Dual<double>(r.y), Dual<double>(r.z)};
        (axis == 0 ? rd.x : axis == 1 ? rd.y : rd.z).d = 1.0;
        Vec3<Dual<double>> f{Dual<double>(0.0), Dual<double>(0.0), Dual<double>(0.0)};
        Surface::compute(rd, Dual<double>(0.5), pd, Dual<double>(0.0), f);
        const Vec3<double> step{axis == 0 ? h : 0.0, axis == 1 ? h : 0.0, axis == 2 ? h : 0.0};
        Vec3<double> ahead, behind;
        Surface::compute(r + step, 0.5, p, 0.0, ahead);
        Surface::compute(r - step, 0.5, p, 0.0, behind);
        const Vec3<double> numeric = (1.0 / (2.0 * h)) * (ahead - behind);
        const Vec3<double> exact{f.x.d, f.y.d, f.z.d};
        EXPECT_LT(norm(exact - numeric), 1e-6 * std::max(norm(numeric), 1.0))
            << "axis " << axis << ": (" << exact.x << ", " << exact.y << ", " << exact.z << ") against (" << numeric.x
            << ", " << numeric.y << ", " << numeric.z << ")";
        Vec3<double> value;
        Surface::compute(r, 0.5, p, 0.0, value);
        EXPECT_DOUBLE_EQ(f.z.v, value.z);
    }
}

TEST(DualNumbers, GiveTheDerivativesOfTheForces) {
    for (const double z : {kSurface - 0.8, kSurface + 0.95, kSurface + 2.0}) {
        const Vec3<double> r{3.0, -4.0, z};
        expect_dual_second_derivatives<SurfaceLennardJonesType1>(
            [](auto tag) { return SurfaceLennardJonesType1::make_params<decltype(tag)>(kSurface, 1.1, kSigma); }, r);
        expect_dual_second_derivatives<SurfaceWCAType2>(
            [](auto tag) { return SurfaceWCAType2::make_params<decltype(tag)>(kSurface, 1.1, kSigma); }, r);
        expect_dual_second_derivatives<SurfaceGeneralLennardJonesType1>(
            [](auto tag) {
                return SurfaceGeneralLennardJonesType1::make_params<decltype(tag)>(kSurface, -0.7, kSigma);
            },
            r);
        expect_dual_second_derivatives<SurfaceIntegratedLennardJonesType2>(
            [](auto tag) {
                return SurfaceIntegratedLennardJonesType2::make_params<decltype(tag)>(kSurface, 0.6, kSigma);
            },
            r);
        ParameterValues v;
        v.set("surfacePosition", {kSurface});
        v.set("epsilon", {2.5});
        v.set("sigma", {kSigma});
        expect_dual_second_derivatives<SurfaceAnchorage>(
            [&](auto tag) { return SurfaceAnchorage::make_params<decltype(tag)>(v, Constants{}); }, r);
        expect_dual_second_derivatives<ParabolaSurface>(
            [&](auto tag) { return ParabolaSurface::make_params<decltype(tag)>(v, Constants{}); }, r);
    }
    for (const Vec3<double>& r :
         {cylindrical(kRadius + 1.0, 0.4, kPlane + 0.6), cylindrical(kRadius - 0.6, 2.0, kPlane - 1.0),
          cylindrical(kRadius - 0.4, -1.0, kPlane + 0.5)})
        expect_dual_second_derivatives<WCAPlainCylinder>(
            [](auto tag) {
                return WCAPlainCylinder::make_params<decltype(tag)>(kPlane, kRadius, kCylinderEpsilon, kCylinderSigma);
            },
            r);
}

TEST(DualNumbers, GiveTheDerivativesOfThePolyhedronForces) {
    const std::vector<Vec3<double>> vertices = cube_vertices<double>();
    const std::vector<Vec3<Dual<double>>> dualVertices = cube_vertices<Dual<double>>();
    const auto make = [&](auto tag) {
        if constexpr (std::is_same_v<decltype(tag), double>)
            return cube_params<double>(vertices);
        else
            return cube_params<Dual<double>>(dualVertices);
    };
    for (const Vec3<double>& r :
         {kCubeCentre + Vec3<double>{0.2, 0.4, kHalfEdge + 0.7}, kCubeCentre + Vec3<double>{kHalfEdge + 0.5, 1.9, 0.3},
          kCubeCentre + Vec3<double>{1.8, -1.9, -1.85}, kCubeCentre + Vec3<double>{-kHalfEdge + 0.6, 0.1, 0.2}})
        expect_dual_second_derivatives<WCAPolyhedronPotential>(make, r);
}

TEST(SinglePrecision, MatchesDouble) {
    for (const double z : {kSurface - 0.8, kSurface + 0.95, kSurface + 2.0}) {
        const Vec3<double> r{3.0, -4.0, z};
        expect_float_matches_double<SurfaceLennardJonesType1>(
            [](auto tag) { return SurfaceLennardJonesType1::make_params<decltype(tag)>(kSurface, 1.1, kSigma); }, r);
        expect_float_matches_double<SurfaceGeneralLennardJonesType2>(
            [](auto tag) {
                return SurfaceGeneralLennardJonesType2::make_params<decltype(tag)>(kSurface, -0.7, kSigma);
            },
            r);
        expect_float_matches_double<SurfaceIntegratedLennardJonesType2>(
            [](auto tag) {
                return SurfaceIntegratedLennardJonesType2::make_params<decltype(tag)>(kSurface, 0.6, kSigma);
            },
            r);
    }
    expect_float_matches_double<SurfaceWCAType1>(
        [](auto tag) { return SurfaceWCAType1::make_params<decltype(tag)>(kSurface, 1.0, kSigma); },
        {1.0, 2.0, kSurface + 0.85});
    for (const Vec3<double>& r :
         {cylindrical(kRadius + 1.0, 0.4, kPlane + 0.8), cylindrical(kRadius - 0.8, 2.0, kPlane - 1.0),
          cylindrical(kRadius - 0.5, -1.0, kPlane + 0.6)})
        expect_float_matches_double<WCAPlainCylinder>(
            [](auto tag) {
                return WCAPlainCylinder::make_params<decltype(tag)>(kPlane, kRadius, kCylinderEpsilon, kCylinderSigma);
            },
            r);
}

}  // namespace
