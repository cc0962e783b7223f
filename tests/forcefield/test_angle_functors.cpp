// HarmonicAngle, KratkyPorod and BestChenHummerAngle against finite differences of their energy, the
// angle from the arc cosine, the conservation laws, their float instantiation, and the straight,
// folded and nearly straight chains where the angle's gradient degenerates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "forcefield/best_chen_hummer_angle.hpp"
#include "forcefield/harmonic_angle.hpp"
#include "forcefield/kratky_porod.hpp"

#include "bonded_test_support.hpp"

namespace structmd {
namespace bonded_test {
namespace {

// Parameter values per sample, in the order of the term's declared parameters: K, theta0.
std::vector<double> harmonic_angle_values(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> K(0.5, 20.0), theta0(0.3, kPi);
    return {K(rng), theta0(rng)};
}

// U from the input-format formula, with the angle computed here.
double harmonic_angle_energy(const std::vector<double>& v, double theta) {
    return 0.5 * v[0] * (theta - v[1]) * (theta - v[1]);
}

TEST(HarmonicAngle, ForceIsMinusGradientOfEnergy) {
    std::mt19937_64 rng(11);
    double worst = 0.0;
    for (const Chain<3>& c : angle_chains(1)) {
        const std::vector<double> v = harmonic_angle_values(rng);
        const auto p = HarmonicAngle::make_params<double>(values_in_order(HarmonicAngle::parameters(), v.data()), kConstants);
        const double error = finite_difference_error<HarmonicAngle>(c.r, p, 1e-3 * v[0]);
        EXPECT_LT(error, kForceTolerance);
        worst = std::max(worst, error);
    }
    report("HarmonicAngle force vs finite differences", worst);
}

TEST(HarmonicAngle, EnergyMatchesAngleFromArcCosine) {
    std::mt19937_64 rng(12);
    double worst = 0.0;
    for (const Chain<3>& c : angle_chains(2)) {
        const std::vector<double> v = harmonic_angle_values(rng);
        const auto p = HarmonicAngle::make_params<double>(values_in_order(HarmonicAngle::parameters(), v.data()), kConstants);
        V force[3];
        const double energy = HarmonicAngle::compute(c.r, p, kBox, force);
        const double theta = angle_by_arc_cosine(c.unwrapped[0], c.unwrapped[1], c.unwrapped[2]);
        const double expected = harmonic_angle_energy(v, theta);
        const double error = std::fabs(energy - expected) / std::max(std::fabs(expected), 1e-3 * v[0]);
        EXPECT_LT(error, 1e-9);
        worst = std::max(worst, error);
    }
    report("HarmonicAngle energy vs formula", worst);
}

TEST(HarmonicAngle, ForcesAndTorquesSumToZero) {
    std::mt19937_64 rng(13);
    Balance worst{0, 0};
    for (const Chain<3>& c : angle_chains(3)) {
        const std::vector<double> v = harmonic_angle_values(rng);
        V force[3];
        HarmonicAngle::compute(c.r, HarmonicAngle::make_params<double>(values_in_order(HarmonicAngle::parameters(), v.data()), kConstants), kBox, force);
        const Balance b = balance_of<3>(c.r, force);
        EXPECT_LT(b.net_force, kBalanceTolerance);
        EXPECT_LT(b.torque, kBalanceTolerance);
        worst = {std::max(worst.net_force, b.net_force), std::max(worst.torque, b.torque)};
    }
    report("HarmonicAngle net force", worst.net_force);
    report("HarmonicAngle net torque", worst.torque);
}

TEST(HarmonicAngle, FloatAgreesWithDouble) {
    std::mt19937_64 rng(14);
    FloatAgreement worst{0, 0};
    for (const Chain<3>& c : angle_chains(4)) {
        const std::vector<double> v = harmonic_angle_values(rng);
        const FloatAgreement a = float_agreement<HarmonicAngle>(c.r, v.data(), 1e-3 * v[0], 1e-3 * v[0]);
        EXPECT_LT(a.energy, kFloatTolerance);
        EXPECT_LT(a.force, kFloatTolerance);
        worst = {std::max(worst.energy, a.energy), std::max(worst.force, a.force)};
    }
    report("HarmonicAngle float vs double energy", worst.energy);
    report("HarmonicAngle float vs double force", worst.force);
}

// Three particles bent by angle theta at r[1], in a randomly oriented plane: r[0] along `along` and
// r[2] in the direction cos(theta) along + sin(theta) across. theta decreases as r[0] moves along
// `across` or r[2] along `towards_first` (the in-plane normal of the second arm towards the first),
// so dtheta/dr0 = -across / |arm0| and dtheta/dr2 = -towards_first / |arm2|.
struct BentChain {
    V r[3];
    V across;
    V towards_first;
};

BentChain bent_chain(std::mt19937_64& rng, double theta, double first_arm, double second_arm) {
    const V along = random_direction(rng);
    const V across = unit(cross_product(along, random_direction(rng)));
    const V vertex{0.3, -0.2, 0.1};
    return {{vertex + first_arm * along, vertex,
             vertex + second_arm * (std::cos(theta) * along + std::sin(theta) * across)},
            across,
            std::sin(theta) * along - std::cos(theta) * across};
}

// The forces -dU/dtheta grad(theta) on a bent chain, from its construction.
void forces_of_bent_chain(const BentChain& c, double dudtheta, double first_arm, double second_arm, V* force) {
    force[0] = (dudtheta / first_arm) * c.across;
    force[2] = (dudtheta / second_arm) * c.towards_first;
    force[1] = -(force[0] + force[2]);
}

// Within 1e-6 rad of pi a finite-difference step would have to be far below the distance to the kink
// at pi; the forces are checked against the exact ones of the construction instead.
TEST(HarmonicAngle, NearlyStraightChainHasFiniteExactForces) {
    std::mt19937_64 rng(15);
    const double K = 7.0, theta0 = 2.0, arm0 = 1.1, arm2 = 0.8;
    const double values[] = {K, theta0};
    const auto p = HarmonicAngle::make_params<double>(values_in_order(HarmonicAngle::parameters(), values), kConstants);
    double worst = 0.0;
    for (int sample = 0; sample < 20; ++sample) {
        const double theta = kPi - 1e-6 * (0.05 + 0.95 * sample / 20.0);
        const BentChain c = bent_chain(rng, theta, arm0, arm2);
        V force[3], expected[3];
        const double energy = HarmonicAngle::compute(c.r, p, kBox, force);
        EXPECT_NEAR(energy, 0.5 * K * (theta - theta0) * (theta - theta0), 1e-9 * energy);
        forces_of_bent_chain(c, K * (theta - theta0), arm0, arm2, expected);
        for (int k = 0; k < 3; ++k) {
            const double error = max_abs(force[k] - expected[k]) / max_abs(expected[0]);
            EXPECT_LT(error, kForceTolerance) << "particle " << k;
            worst = std::max(worst, error);
        }
        const Balance b = balance_of<3>(c.r, force);
        EXPECT_LT(b.net_force, kBalanceTolerance);
        EXPECT_LT(b.torque, kBalanceTolerance);
    }
    report("HarmonicAngle within 1e-6 of pi: force vs exact", worst);
}

// At exactly 0 or pi the force is the limit of the force of chains bent slightly in its own
// direction: finite, of magnitude |dU/dtheta| / arm on the end particle, balanced.
TEST(HarmonicAngle, StraightOrFoldedChainForceIsAOneSidedLimit) {
    const double K = 3.0, arm0 = 1.1, arm2 = 0.7;
    for (const double theta0 : {0.5, 2.5}) {
        const double values[] = {K, theta0};
        const auto p = HarmonicAngle::make_params<double>(values_in_order(HarmonicAngle::parameters(), values), kConstants);
        for (const double theta : {0.0, kPi}) {
            const V along = unit(V{0.3, -0.8, 0.5});
            const V vertex{0.1, 0.2, -0.3};
            const V r[3] = {vertex + arm0 * along, vertex, vertex + (arm2 * std::cos(theta)) * along};
            V force[3];
            const double energy = HarmonicAngle::compute(r, p, kBox, force);
            EXPECT_DOUBLE_EQ(energy, 0.5 * K * (theta - theta0) * (theta - theta0));
            ASSERT_NEAR(length(force[0]), K * std::fabs(theta - theta0) / arm0, 1e-12);
            EXPECT_NEAR(dot(force[0], along), 0.0, 1e-12);
            const Balance b = balance_of<3>(r, force);
            EXPECT_LT(b.net_force, kBalanceTolerance);
            EXPECT_LT(b.torque, kBalanceTolerance);

            // Bending r[2] off the line within the plane of the force, to the side where theta is
            // nearer theta0 (the force on r[0] is dU/dtheta times the unit normal towards r[2]), the
            // forces of the bent chain tend to those at the line.
            const double tilt = 1e-7;
            const V towards_r2 = (theta > theta0 ? 1.0 : -1.0) * unit(force[0]);
            const V bent[3] = {r[0], r[1], r[2] + (arm2 * tilt) * towards_r2};
            V bent_force[3];
            HarmonicAngle::compute(bent, p, kBox, bent_force);
            for (int k = 0; k < 3; ++k)
                EXPECT_LT(max_abs(bent_force[k] - force[k]), 1e-5 * length(force[0]))
                    << "theta " << theta << " theta0 " << theta0 << " particle " << k;
        }
    }
}

TEST(HarmonicAngle, StraightChainAtItsRestAngleFeelsNoForce) {
    const double values[] = {4.0, kPi};
    const V r[3] = {{1.0, 0.5, 0.0}, {0.0, 0.0, 0.0}, {-2.0, -1.0, 0.0}};
    V force[3];
    EXPECT_DOUBLE_EQ(HarmonicAngle::compute(r, HarmonicAngle::make_params<double>(values_in_order(HarmonicAngle::parameters(), values), kConstants), kBox, force), 0.0);
    for (const V& f : force) EXPECT_EQ(max_abs(f), 0.0);
}

TEST(HarmonicAngle, ZeroLengthArmHasNoAngle) {
    const double values[] = {4.0, 1.0};
    const V r[3] = {{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {1.0, 0.0, 0.0}};
    V force[3];
    EXPECT_TRUE(std::isnan(HarmonicAngle::compute(r, HarmonicAngle::make_params<double>(values_in_order(HarmonicAngle::parameters(), values), kConstants), kBox, force)));
    for (const V& f : force) EXPECT_TRUE(std::isnan(f.x));
}

TEST(KratkyPorod, ForceIsMinusGradientOfEnergy) {
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> K(0.5, 20.0);
    double worst = 0.0;
    for (const Chain<3>& c : angle_chains(5)) {
        const double values[] = {K(rng)};
        const double error =
            finite_difference_error<KratkyPorod>(c.r, KratkyPorod::make_params<double>(values_in_order(KratkyPorod::parameters(), values), kConstants), 1e-3 * values[0]);
        EXPECT_LT(error, kForceTolerance);
        worst = std::max(worst, error);
    }
    report("KratkyPorod force vs finite differences", worst);
}

TEST(KratkyPorod, EnergyMatchesAngleFromArcCosine) {
    std::mt19937_64 rng(22);
    std::uniform_real_distribution<double> K(0.5, 20.0);
    double worst = 0.0;
    for (const Chain<3>& c : angle_chains(6)) {
        const double values[] = {K(rng)};
        V force[3];
        const double energy = KratkyPorod::compute(c.r, KratkyPorod::make_params<double>(values_in_order(KratkyPorod::parameters(), values), kConstants), kBox, force);
        const double theta = angle_by_arc_cosine(c.unwrapped[0], c.unwrapped[1], c.unwrapped[2]);
        const double expected = values[0] * (1.0 + std::cos(theta));
        const double error = std::fabs(energy - expected) / std::max(expected, 1e-3 * values[0]);
        EXPECT_LT(error, 1e-9);
        worst = std::max(worst, error);
    }
    report("KratkyPorod energy vs formula", worst);
}

TEST(KratkyPorod, ForcesAndTorquesSumToZero) {
    std::mt19937_64 rng(23);
    Balance worst{0, 0};
    std::uniform_real_distribution<double> K(0.5, 20.0);
    for (const Chain<3>& c : angle_chains(7)) {
        const double values[] = {K(rng)};
        V force[3];
        KratkyPorod::compute(c.r, KratkyPorod::make_params<double>(values_in_order(KratkyPorod::parameters(), values), kConstants), kBox, force);
        const Balance b = balance_of<3>(c.r, force);
        EXPECT_LT(b.net_force, kBalanceTolerance);
        EXPECT_LT(b.torque, kBalanceTolerance);
        worst = {std::max(worst.net_force, b.net_force), std::max(worst.torque, b.torque)};
    }
    report("KratkyPorod net force", worst.net_force);
    report("KratkyPorod net torque", worst.torque);
}

TEST(KratkyPorod, FloatAgreesWithDouble) {
    std::mt19937_64 rng(24);
    std::uniform_real_distribution<double> K(0.5, 20.0);
    FloatAgreement worst{0, 0};
    for (const Chain<3>& c : angle_chains(8)) {
        const double values[] = {K(rng)};
        const FloatAgreement a = float_agreement<KratkyPorod>(c.r, values, 1e-3 * values[0], 1e-3 * values[0]);
        EXPECT_LT(a.energy, kFloatTolerance);
        EXPECT_LT(a.force, kFloatTolerance);
        worst = {std::max(worst.energy, a.energy), std::max(worst.force, a.force)};
    }
    report("KratkyPorod float vs double energy", worst.energy);
    report("KratkyPorod float vs double force", worst.force);
}

// U = K (1 + cos theta) is smooth through the straight chain: the force there is zero, and within
// 1e-6 rad of it the forces are the exact ones of the construction.
TEST(KratkyPorod, NearlyStraightChainIsSmooth) {
    std::mt19937_64 rng(25);
    const double K = 5.0, arm0 = 1.1, arm2 = 0.8;
    const double values[] = {K};
    const auto p = KratkyPorod::make_params<double>(values_in_order(KratkyPorod::parameters(), values), kConstants);
    const V straight[3] = {{1.0, 0.5, 0.0}, {0.0, 0.0, 0.0}, {-2.0, -1.0, 0.0}};
    V force[3];
    EXPECT_NEAR(KratkyPorod::compute(straight, p, kBox, force), 0.0, 1e-15);
    for (const V& f : force) EXPECT_LT(max_abs(f), 1e-14);
    double worst = 0.0;
    for (int sample = 0; sample < 20; ++sample) {
        const double theta = kPi - 1e-6 * (0.05 + 0.95 * sample / 20.0);
        const BentChain c = bent_chain(rng, theta, arm0, arm2);
        V expected[3];
        KratkyPorod::compute(c.r, p, kBox, force);
        forces_of_bent_chain(c, -K * std::sin(theta), arm0, arm2, expected);
        for (int k = 0; k < 3; ++k) {
            const double error = max_abs(force[k] - expected[k]) / max_abs(expected[0]);
            EXPECT_LT(error, kForceTolerance) << "particle " << k;
            worst = std::max(worst, error);
        }
    }
    report("KratkyPorod within 1e-6 of pi: force vs exact", worst);
}

// ---- BestChenHummerAngle: no parameters, the paper's constants in kcal/mol and radians ----

// U of Best, Chen and Hummer as the input format writes it: the logarithm of the sum of the two
// exponentials, taken as written (no log-sum-exp).
double best_chen_hummer_energy(double theta) {
    const double gamma = 0.1;
    const double alpha = std::exp(-gamma * (106.4 * (theta - 1.60) * (theta - 1.60) + 4.3));
    const double beta = std::exp(-gamma * 26.3 * (theta - 2.27) * (theta - 2.27));
    return -std::log(alpha + beta) / gamma;
}

using BCH = BestChenHummerAngle;
const auto kBchParams = BCH::make_params<double>(values_in_order(BCH::parameters(), nullptr), kConstants);

TEST(BestChenHummerAngle, ForceIsMinusGradientOfEnergy) {
    double worst = 0.0;
    for (const Chain<3>& c : angle_chains(61)) {
        const double error = finite_difference_error<BCH>(c.r, kBchParams, 1e-3);
        EXPECT_LT(error, kForceTolerance);
        worst = std::max(worst, error);
    }
    report("BestChenHummerAngle force vs finite differences", worst);
}

TEST(BestChenHummerAngle, EnergyMatchesAngleFromArcCosine) {
    double worst = 0.0;
    for (const Chain<3>& c : angle_chains(62)) {
        V force[3];
        const double energy = BCH::compute(c.r, kBchParams, kBox, force);
        const double theta = angle_by_arc_cosine(c.unwrapped[0], c.unwrapped[1], c.unwrapped[2]);
        const double expected = best_chen_hummer_energy(theta);
        // U crosses zero near the beta well: relative to 1 kcal/mol there.
        const double error = std::fabs(energy - expected) / std::max(std::fabs(expected), 1.0);
        EXPECT_LT(error, 1e-9);
        worst = std::max(worst, error);
    }
    report("BestChenHummerAngle energy vs formula", worst);
}

TEST(BestChenHummerAngle, ForcesAndTorquesSumToZero) {
    Balance worst{0, 0};
    for (const Chain<3>& c : angle_chains(63)) {
        V force[3];
        BCH::compute(c.r, kBchParams, kBox, force);
        const Balance b = balance_of<3>(c.r, force);
        EXPECT_LT(b.net_force, kBalanceTolerance);
        EXPECT_LT(b.torque, kBalanceTolerance);
        worst = {std::max(worst.net_force, b.net_force), std::max(worst.torque, b.torque)};
    }
    report("BestChenHummerAngle net force", worst.net_force);
    report("BestChenHummerAngle net torque", worst.torque);
}

TEST(BestChenHummerAngle, FloatAgreesWithDouble) {
    FloatAgreement worst{0, 0};
    for (const Chain<3>& c : angle_chains(64)) {
        const FloatAgreement a = float_agreement<BCH>(c.r, nullptr, 1.0, 1.0);
        EXPECT_LT(a.energy, kFloatTolerance);
        EXPECT_LT(a.force, kFloatTolerance);
        worst = {std::max(worst.energy, a.energy), std::max(worst.force, a.force)};
    }
    report("BestChenHummerAngle float vs double energy", worst.energy);
    report("BestChenHummerAngle float vs double force", worst.force);
}

// Over the whole range of theta, the straight and folded chains included, the log-sum-exp form
// equals the formula, and U has two wells: a helical one, pulled from theta_alpha = 1.60 towards the
// extended one by their mixing (to 1.704), and the extended one near theta_beta = 2.27 (at 2.251),
// separated by a barrier.
TEST(BestChenHummerAngle, TwoWellsHelicalAndExtended) {
    const double arm0 = 1.1, arm2 = 0.9;
    const V along = unit(V{0.3, -0.8, 0.5});
    const V across = unit(cross_product(along, V{1.0, 0.2, -0.4}));
    const V vertex{0.1, 0.2, -0.3};
    std::vector<double> energies;
    const int steps = 31400;
    double worst = 0.0;
    for (int k = 0; k <= steps; ++k) {
        const double theta = kPi * k / steps;
        const V r[3] = {vertex + arm0 * along, vertex,
                        vertex + arm2 * (std::cos(theta) * along + std::sin(theta) * across)};
        V force[3];
        const double energy = BCH::compute(r, kBchParams, kBox, force);
        ASSERT_TRUE(std::isfinite(energy) && std::isfinite(force[0].x) && std::isfinite(force[2].x)) << theta;
        worst = std::max(worst, std::fabs(energy - best_chen_hummer_energy(theta)) /
                                    std::max(std::fabs(best_chen_hummer_energy(theta)), 1.0));
        energies.push_back(energy);
    }
    EXPECT_LT(worst, 1e-9);
    std::vector<int> minima;
    for (int k = 1; k < steps; ++k)
        if (energies[k] < energies[k - 1] && energies[k] < energies[k + 1]) minima.push_back(k);
    ASSERT_EQ(minima.size(), 2u);
    EXPECT_NEAR(kPi * minima[0] / steps, 1.704, 1e-3);
    EXPECT_NEAR(kPi * minima[1] / steps, 2.251, 1e-3);
    const double barrier = *std::max_element(energies.begin() + minima[0], energies.begin() + minima[1]);
    EXPECT_GT(barrier, energies[minima[0]] + 0.1);
    EXPECT_GT(barrier, energies[minima[1]] + 0.1);
    std::printf("[ wells    ] BestChenHummerAngle: U = %.4f at %.4f, %.4f at %.4f, barrier %.4f kcal/mol\n",
                energies[minima[0]], kPi * minima[0] / steps, energies[minima[1]], kPi * minima[1] / steps, barrier);
    report("BestChenHummerAngle energy vs formula over [0, pi]", worst);
}

// dU/dtheta does not vanish at pi: the straight chain feels the one-sided limit of the force,
// |F_0| = |dU/dtheta| / |arm 0|, balanced.
TEST(BestChenHummerAngle, StraightChainForceIsAOneSidedLimit) {
    const double arm0 = 1.1, arm2 = 0.7;
    const V along = unit(V{0.3, -0.8, 0.5});
    const V vertex{0.1, 0.2, -0.3};
    const V r[3] = {vertex + arm0 * along, vertex, vertex - arm2 * along};
    V force[3];
    const double energy = BCH::compute(r, kBchParams, kBox, force);
    EXPECT_NEAR(energy, best_chen_hummer_energy(kPi), 1e-12 * std::fabs(energy));
    const double h = 1e-6;
    const double slope = (best_chen_hummer_energy(kPi) - best_chen_hummer_energy(kPi - h)) / h;
    EXPECT_NEAR(length(force[0]), std::fabs(slope) / arm0, 1e-5 * std::fabs(slope) / arm0);
    const Balance b = balance_of<3>(r, force);
    EXPECT_LT(b.net_force, kBalanceTolerance);
    EXPECT_LT(b.torque, kBalanceTolerance);
}

}  // namespace
}  // namespace bonded_test
}  // namespace structmd
