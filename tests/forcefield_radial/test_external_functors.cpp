// External single-particle potentials: energies against the formulas of the input specification
// (written out here independently of the functors), forces against a central finite difference of
// the functor's energy in x, y and z at several times, with moving walls and with their clamps
// active, and single precision against double.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "forcefield/external_constant_force.hpp"
#include "forcefield/plates.hpp"
#include "forcefield/spherical_shell.hpp"

using namespace structmd;

namespace {

constexpr double kEnergyTolerance = 1e-10;          // relative, double against the formula
constexpr double kForceTolerance = 1e-6;            // relative to |F|, against the central difference
constexpr double kSinglePrecisionTolerance = 1e-4;  // relative, float against double

struct WorstErrors {
    double energy = 0.0;
    double force = 0.0;
    double single_precision = 0.0;
};
WorstErrors worst;

class PrintWorstErrors : public ::testing::Environment {
public:
    void TearDown() override {
        std::printf("worst relative errors: energy %.3g, force %.3g, float against double %.3g\n", worst.energy,
                    worst.force, worst.single_precision);
    }
};
::testing::Environment* const print_worst_errors = ::testing::AddGlobalTestEnvironment(new PrintWorstErrors);

double norm(Vec3<double> v) { return std::sqrt(dot(v, v)); }

std::string describe(Vec3<double> r, double time) {
    return "r = (" + std::to_string(r.x) + ", " + std::to_string(r.y) + ", " + std::to_string(r.z) +
           "), t = " + std::to_string(time);
}

template <class External>
double energy_at(Vec3<double> r, double radius, const typename External::template Params<double>& p, double time) {
    Vec3<double> ignored;
    return External::compute(r, radius, p, time, ignored);
}

// The force equals minus the central difference of the energy along each axis, and the energy the
// given value.
template <class External>
void expect_energy_and_force(Vec3<double> r, double radius, const typename External::template Params<double>& p,
                             double time, double expected_energy) {
    SCOPED_TRACE(describe(r, time));
    Vec3<double> force;
    const double energy = External::compute(r, radius, p, time, force);
    const double energy_error = std::fabs(energy - expected_energy) / std::fabs(expected_energy);
    EXPECT_LT(energy_error, kEnergyTolerance) << energy << " against " << expected_energy;
    const double h = 1e-6;
    const auto minus_slope = [&](Vec3<double> axis) {
        const double ahead = energy_at<External>(r + h * axis, radius, p, time);
        const double behind = energy_at<External>(r - h * axis, radius, p, time);
        return -(ahead - behind) / (2.0 * h);
    };
    const Vec3<double> numeric{minus_slope({1, 0, 0}), minus_slope({0, 1, 0}), minus_slope({0, 0, 1})};
    const double force_error = norm(force - numeric) / norm(numeric);
    EXPECT_LT(force_error, kForceTolerance) << "force (" << force.x << ", " << force.y << ", " << force.z
                                            << ") against (" << numeric.x << ", " << numeric.y << ", " << numeric.z
                                            << ")";
    worst.energy = std::max(worst.energy, energy_error);
    worst.force = std::max(worst.force, force_error);
}

// make(tag) builds the Params of the precision of tag; energy and force in float agree with double.
template <class External, class Make>
void expect_float_matches_double(Make make, Vec3<double> r, double radius, double time) {
    SCOPED_TRACE(describe(r, time));
    const auto pd = make(double{});
    const auto pf = make(float{});
    Vec3<double> fd;
    Vec3<float> ff;
    const double ed = External::compute(r, radius, pd, time, fd);
    const float ef = External::compute(Vec3<float>{float(r.x), float(r.y), float(r.z)}, float(radius), pf,
                                       float(time), ff);
    const double energy_error = std::fabs(ef - ed) / std::fabs(ed);
    const double force_error = norm(Vec3<double>{ff.x - fd.x, ff.y - fd.y, ff.z - fd.z}) / norm(fd);
    EXPECT_LT(energy_error, kSinglePrecisionTolerance);
    EXPECT_LT(force_error, kSinglePrecisionTolerance);
    worst.single_precision = std::max({worst.single_precision, energy_error, force_error});
}

TEST(ExternalConstantForce, ForceIsExactAndEnergyZero) {
    const Vec3<double> applied{0.5, -1.25, 3.0};
    const auto pd = ExternalConstantForce::make_params<double>(applied);
    const auto pf = ExternalConstantForce::make_params<float>(applied);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> coordinate(-20.0, 20.0);
    for (int k = 0; k < 8; ++k) {
        const Vec3<double> r{coordinate(rng), coordinate(rng), coordinate(rng)};
        const double time = 3.7 * k;
        Vec3<double> fd;
        EXPECT_EQ(ExternalConstantForce::compute(r, 0.5, pd, time, fd), 0.0);
        EXPECT_EQ(fd.x, applied.x);
        EXPECT_EQ(fd.y, applied.y);
        EXPECT_EQ(fd.z, applied.z);
        Vec3<float> ff;
        EXPECT_EQ(ExternalConstantForce::compute(Vec3<float>{float(r.x), float(r.y), float(r.z)}, 0.5f, pf,
                                                 float(time), ff),
                  0.0f);
        EXPECT_EQ(ff.x, 0.5f);
        EXPECT_EQ(ff.y, -1.25f);
        EXPECT_EQ(ff.z, 3.0f);
    }
}

// Plates: initial separation 10, moving at v, separation kept within [4, 14].
constexpr double kPlatesSeparation = 10.0;
constexpr double kPlatesEpsilon = 1.5;
constexpr double kPlatesSigma = 0.8;
constexpr double kMinSeparation = 4.0;
constexpr double kMaxSeparation = 14.0;

Plates::Params<double> plates(double velocity) {
    return Plates::make_params<double>(kPlatesSeparation, kPlatesEpsilon, kPlatesSigma, velocity, kMinSeparation,
                                       kMaxSeparation);
}

double plates_energy(double velocity, double time, double z) {
    const double separation = std::clamp(kPlatesSeparation + 2.0 * velocity * time, kMinSeparation, kMaxSeparation);
    const double top = separation / 2.0, bottom = -separation / 2.0;
    return kPlatesEpsilon * (std::pow(kPlatesSigma / (top - z), 12) + std::pow(kPlatesSigma / (z - bottom), 12));
}

TEST(Plates, ForceIsMinusTheGradientAsThePlatesMove) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> lateral(-30.0, 30.0);
    std::uniform_real_distribution<double> fraction(-0.9, 0.9);
    // Compressing and expanding; the later times reach the clamps (t = 10: separation 2 -> 4, and 16 -> 14).
    for (const double velocity : {-0.4, 0.1, 0.3}) {
        for (const double time : {0.0, 1.5, 4.0, 10.0}) {
            const double half = 0.5 * std::clamp(kPlatesSeparation + 2.0 * velocity * time, kMinSeparation,
                                                 kMaxSeparation);
            for (int k = 0; k < 6; ++k) {
                const Vec3<double> r{lateral(rng), lateral(rng), fraction(rng) * half};
                expect_energy_and_force<Plates>(r, 0.7, plates(velocity), time, plates_energy(velocity, time, r.z));
            }
        }
    }
}

TEST(Plates, SeparationIsClampedToItsLimits) {
    // At z = 0 the energy is 2 eps (sigma / (S/2))^12 for separation S.
    const auto at_centre = [](double velocity, double time) {
        return energy_at<Plates>({0.0, 0.0, 0.0}, 0.0, plates(velocity), time);
    };
    const auto expected = [](double separation) {
        return 2.0 * kPlatesEpsilon * std::pow(kPlatesSigma / (separation / 2.0), 12);
    };
    EXPECT_NEAR(at_centre(0.3, 2.0) / expected(11.2), 1.0, 1e-12);
    EXPECT_NEAR(at_centre(-0.4, 10.0) / expected(kMinSeparation), 1.0, 1e-12);
    EXPECT_NEAR(at_centre(-0.4, 1000.0) / expected(kMinSeparation), 1.0, 1e-12);
    EXPECT_NEAR(at_centre(0.3, 10.0) / expected(kMaxSeparation), 1.0, 1e-12);
    // The default upper limit is no limit.
    const auto unbounded = Plates::make_params<double>(kPlatesSeparation, kPlatesEpsilon, kPlatesSigma, 0.3, 0.0,
                                                       std::numeric_limits<double>::infinity());
    EXPECT_NEAR(energy_at<Plates>({0.0, 0.0, 0.0}, 0.0, unbounded, 10.0) / expected(16.0), 1.0, 1e-12);
}

TEST(Plates, PushParticlesAwayFromEachPlateAndNotSideways) {
    const auto p = plates(0.0);
    Vec3<double> near_top, near_bottom;
    Plates::compute({1.0, 2.0, 4.0}, 0.0, p, 0.0, near_top);
    Plates::compute({-3.0, 0.5, -4.0}, 0.0, p, 0.0, near_bottom);
    EXPECT_LT(near_top.z, 0.0);
    EXPECT_GT(near_bottom.z, 0.0);
    EXPECT_EQ(near_top.x, 0.0);
    EXPECT_EQ(near_top.y, 0.0);
}

// Shell: centre off the origin, radius 6 moving at v, kept within [3, 8].
const Vec3<double> kShellCenter{1.0, -2.0, 0.5};
constexpr double kShellRadius = 6.0;
constexpr double kShellEpsilon = 2.0;
constexpr double kShellSigma = 0.9;
constexpr double kMinShellRadius = 3.0;
constexpr double kMaxShellRadius = 8.0;
constexpr double kParticleRadius = 0.4;

SphericalShell::Params<double> shell(double velocity) {
    return SphericalShell::make_params<double>(kShellCenter, kShellRadius, kShellEpsilon, kShellSigma,
                                               kMinShellRadius, kMaxShellRadius, velocity);
}

double shell_radius(double velocity, double time) {
    return std::clamp(kShellRadius + velocity * time, kMinShellRadius, kMaxShellRadius);
}

double shell_energy(double velocity, double time, Vec3<double> r, double particle_radius) {
    const double d = norm(r - kShellCenter);
    return kShellEpsilon * std::pow((kShellSigma + particle_radius) / (d - shell_radius(velocity, time)), 12);
}

// A point at distance d from the shell's centre in a random direction.
Vec3<double> at_distance(std::mt19937& rng, double d) {
    std::normal_distribution<double> gaussian;
    const Vec3<double> direction{gaussian(rng), gaussian(rng), gaussian(rng)};
    return kShellCenter + (d / norm(direction)) * direction;
}

TEST(SphericalShell, ForceIsMinusTheGradientAsTheShellMoves) {
    std::mt19937 rng(77);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    // Shrinking and growing; the later times reach the clamps (t = 8: radius 2 -> 3, and 10 -> 8).
    for (const double velocity : {-0.5, 0.25, 0.5}) {
        for (const double time : {0.0, 2.0, 8.0}) {
            const double radius = shell_radius(velocity, time);
            for (int k = 0; k < 4; ++k) {
                const Vec3<double> inside = at_distance(rng, 0.2 + (radius - 1.2) * unit(rng));
                const Vec3<double> outside = at_distance(rng, radius + 0.8 + 3.0 * unit(rng));
                for (const Vec3<double> r : {inside, outside})
                    expect_energy_and_force<SphericalShell>(r, kParticleRadius, shell(velocity), time,
                                                            shell_energy(velocity, time, r, kParticleRadius));
            }
        }
    }
}

TEST(SphericalShell, RadiusIsClampedToItsLimits) {
    const Vec3<double> r = kShellCenter + Vec3<double>{1.0, 0.0, 0.0};
    const auto expected = [](double radius) {
        return kShellEpsilon * std::pow((kShellSigma + kParticleRadius) / (1.0 - radius), 12);
    };
    const auto p = shell(-0.5);
    EXPECT_NEAR(energy_at<SphericalShell>(r, kParticleRadius, p, 2.0) / expected(5.0), 1.0, 1e-12);
    EXPECT_NEAR(energy_at<SphericalShell>(r, kParticleRadius, p, 10.0) / expected(kMinShellRadius), 1.0, 1e-12);
    EXPECT_NEAR(energy_at<SphericalShell>(r, kParticleRadius, p, 500.0) / expected(kMinShellRadius), 1.0, 1e-12);
    EXPECT_NEAR(energy_at<SphericalShell>(r, kParticleRadius, shell(0.5), 10.0) / expected(kMaxShellRadius), 1.0,
                1e-12);
}

TEST(SphericalShell, PushesParticlesAwayFromTheShellAndIsFiniteAtTheCentre) {
    const auto p = shell(0.0);
    Vec3<double> force;
    const Vec3<double> inside = kShellCenter + Vec3<double>{0.0, 4.5, 0.0};
    SphericalShell::compute(inside, kParticleRadius, p, 0.0, force);
    EXPECT_LT(dot(force, inside - kShellCenter), 0.0);
    const Vec3<double> outside = kShellCenter + Vec3<double>{-7.0, 0.0, 1.0};
    SphericalShell::compute(outside, kParticleRadius, p, 0.0, force);
    EXPECT_GT(dot(force, outside - kShellCenter), 0.0);
    const double at_centre = SphericalShell::compute(kShellCenter, kParticleRadius, p, 0.0, force);
    EXPECT_NEAR(at_centre / (kShellEpsilon * std::pow((kShellSigma + kParticleRadius) / kShellRadius, 12)), 1.0,
                1e-12);
    EXPECT_EQ(force.x, 0.0);
    EXPECT_EQ(force.y, 0.0);
    EXPECT_EQ(force.z, 0.0);
}

TEST(SinglePrecision, MatchesDouble) {
    for (const double velocity : {-0.4, 0.3}) {
        const auto make_plates = [velocity](auto tag) {
            return Plates::make_params<decltype(tag)>(kPlatesSeparation, kPlatesEpsilon, kPlatesSigma, velocity,
                                                      kMinSeparation, kMaxSeparation);
        };
        for (const double time : {0.0, 2.0, 10.0}) {
            expect_float_matches_double<Plates>(make_plates, {1.5, -2.0, 1.1}, 0.5, time);
            expect_float_matches_double<Plates>(make_plates, {-7.0, 3.0, -1.6}, 0.5, time);
        }
    }
    for (const double velocity : {-0.5, 0.5}) {
        const auto make_shell = [velocity](auto tag) {
            using R = decltype(tag);
            return SphericalShell::make_params<R>(kShellCenter, kShellRadius, kShellEpsilon, kShellSigma,
                                                  kMinShellRadius, kMaxShellRadius, velocity);
        };
        for (const double time : {0.0, 3.0, 10.0}) {
            expect_float_matches_double<SphericalShell>(make_shell, kShellCenter + Vec3<double>{0.5, 0.7, -1.0},
                                                        kParticleRadius, time);
            expect_float_matches_double<SphericalShell>(make_shell, kShellCenter + Vec3<double>{6.0, -5.0, 4.0},
                                                        kParticleRadius, time);
        }
    }
}

}  // namespace
