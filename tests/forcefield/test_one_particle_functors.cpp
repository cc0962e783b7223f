// The one-particle terms: FixedHarmonic against finite differences of its energy, the nearest image
// of its point found by search, its float instantiation and the particle sitting on the point; and
// ConstantForceBond's force and zero energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "forcefield/constant_force_bond.hpp"
#include "forcefield/fixed_harmonic.hpp"

#include "bonded_test_support.hpp"

namespace structmd {
namespace bonded_test {
namespace {

// The distance from r to the nearest periodic image of point, by searching the 27 nearest images.
double nearest_image_distance(V point, V r) {
    double best = 1e300;
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k) {
                const V image = point + V{i * kBox.length.x, j * kBox.length.y, k * kBox.length.z};
                best = std::min(best, length(image - r));
            }
    return best;
}

// A wrapped particle position and a point, half of them on opposite sides of a box face so that
// the nearest image of the point lies across the boundary.
struct Tether {
    V r[1];
    std::vector<double> values;  // K, r0, px, py, pz
};

std::vector<Tether> tethers(unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit_interval(0.0, 1.0), K(0.5, 20.0), r0(0.0, 0.6);
    std::vector<Tether> result;
    for (int sample = 0; sample < kSamples; ++sample) {
        V particle{(unit_interval(rng) - 0.5) * kBox.length.x, (unit_interval(rng) - 0.5) * kBox.length.y,
                   (unit_interval(rng) - 0.5) * kBox.length.z};
        V point = particle + (0.1 + 1.0 * unit_interval(rng)) * random_direction(rng);
        if (sample % 2 == 1) {
            particle.x = -0.5 * kBox.length.x + 0.2 * unit_interval(rng);
            point.x = 0.5 * kBox.length.x - 0.2 * unit_interval(rng);
        }
        result.push_back({{kBox.wrap(particle)}, {K(rng), r0(rng), point.x, point.y, point.z}});
    }
    return result;
}

TEST(FixedHarmonic, ForceIsMinusGradientOfEnergy) {
    double worst = 0.0;
    for (const Tether& t : tethers(51)) {
        const double error = finite_difference_error<FixedHarmonic>(
            t.r, FixedHarmonic::make_params<double>(values_in_order(FixedHarmonic::parameters(), t.values.data()), kConstants), 1e-3 * t.values[0]);
        EXPECT_LT(error, kForceTolerance);
        worst = std::max(worst, error);
    }
    report("FixedHarmonic force vs finite differences", worst);
}

TEST(FixedHarmonic, EnergyUsesTheNearestImageOfThePoint) {
    double worst = 0.0;
    int across = 0;
    for (const Tether& t : tethers(52)) {
        V force[1];
        const double energy =
            FixedHarmonic::compute(t.r, FixedHarmonic::make_params<double>(values_in_order(FixedHarmonic::parameters(), t.values.data()), kConstants), kBox, force);
        const V point{t.values[2], t.values[3], t.values[4]};
        const double d = nearest_image_distance(point, t.r[0]);
        across += d < length(point - t.r[0]) - 1e-9;
        const double expected = 0.5 * t.values[0] * (d - t.values[1]) * (d - t.values[1]);
        const double error = std::fabs(energy - expected) / std::max(expected, 1e-6 * t.values[0]);
        EXPECT_LT(error, 1e-9);
        worst = std::max(worst, error);
    }
    EXPECT_GT(across, kSamples / 5) << "too few points lie across the boundary to test it";
    report("FixedHarmonic energy vs formula", worst);
}

TEST(FixedHarmonic, PointOutsideTheBoxActsThroughItsImage) {
    const double inside[] = {3.0, 0.2, 0.4, -0.3, 0.9};
    const double outside[] = {3.0, 0.2, 0.4 + 2.0 * kBox.length.x, -0.3 - kBox.length.y, 0.9 + 3.0 * kBox.length.z};
    const V r[1] = {{-0.1, 0.2, 0.3}};
    V f_in[1], f_out[1];
    const double e_in = FixedHarmonic::compute(r, FixedHarmonic::make_params<double>(values_in_order(FixedHarmonic::parameters(), inside), kConstants), kBox, f_in);
    const double e_out = FixedHarmonic::compute(r, FixedHarmonic::make_params<double>(values_in_order(FixedHarmonic::parameters(), outside), kConstants), kBox, f_out);
    EXPECT_NEAR(e_out, e_in, 1e-12);
    EXPECT_LT(max_abs(f_out[0] - f_in[0]), 1e-12);
}

TEST(FixedHarmonic, FloatAgreesWithDouble) {
    FloatAgreement worst{0, 0};
    for (const Tether& t : tethers(53)) {
        const FloatAgreement a = float_agreement<FixedHarmonic>(t.r, t.values.data(), 1e-3 * t.values[0], 1e-3 * t.values[0]);
        EXPECT_LT(a.energy, kFloatTolerance);
        EXPECT_LT(a.force, kFloatTolerance);
        worst = {std::max(worst.energy, a.energy), std::max(worst.force, a.force)};
    }
    report("FixedHarmonic float vs double energy", worst.energy);
    report("FixedHarmonic float vs double force", worst.force);
}

TEST(FixedHarmonic, ParticleOnThePoint) {
    const V r[1] = {{0.4, -0.3, 0.9}};
    V force[1];
    // r0 = 0: the minimum of U, no force.
    const double at_rest[] = {3.0, 0.0, 0.4, -0.3, 0.9};
    EXPECT_EQ(FixedHarmonic::compute(r, FixedHarmonic::make_params<double>(values_in_order(FixedHarmonic::parameters(), at_rest), kConstants), kBox, force), 0.0);
    EXPECT_EQ(max_abs(force[0]), 0.0);
    // r0 > 0: no direction to push along; zero force and the finite energy 1/2 K r0^2.
    const double stretched[] = {3.0, 0.5, 0.4, -0.3, 0.9};
    EXPECT_DOUBLE_EQ(FixedHarmonic::compute(r, FixedHarmonic::make_params<double>(values_in_order(FixedHarmonic::parameters(), stretched), kConstants), kBox, force),
                     0.5 * 3.0 * 0.25);
    EXPECT_EQ(max_abs(force[0]), 0.0);
}

TEST(ConstantForceBond, AppliesTheGivenForceWithNoEnergy) {
    const double values[] = {0.25, -1.5, 3.0};
    const V r[1] = {{0.4, -0.3, 0.9}};
    V force[1];
    EXPECT_EQ(ConstantForceBond::compute(r, ConstantForceBond::make_params<double>(values_in_order(ConstantForceBond::parameters(), values), kConstants), kBox, force), 0.0);
    EXPECT_EQ(force[0].x, 0.25);
    EXPECT_EQ(force[0].y, -1.5);
    EXPECT_EQ(force[0].z, 3.0);
    const FloatAgreement a = float_agreement<ConstantForceBond>(r, values, 1.0, 1.0);
    EXPECT_EQ(a.energy, 0.0);
    EXPECT_EQ(a.force, 0.0);
}

}  // namespace
}  // namespace bonded_test
}  // namespace structmd
