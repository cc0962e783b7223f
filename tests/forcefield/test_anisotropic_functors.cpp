// The anisotropic harmonic springs, ["Bond2","HarmonicAnisotropic"] and
// ["Bond1","FixedHarmonicAnisotropic"]: forces against finite differences of their energy, the energy
// against U = sum_a 1/2 K_a (|d_a| - r0_a)^2 with d taken here from unwrapped positions (or the
// nearest image of the point, found by search), the symmetries of |d_a|, the cusp at d_a = 0, and the
// float instantiation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "forcefield/harmonic_anisotropic.hpp"

#include "bonded_test_support.hpp"

namespace structmd {
namespace bonded_test {
namespace {

// U from the input-format formula: K and r0 are the first six values, in the schema's order.
double anisotropic_energy(const double* values, V d) {
    double energy = 0.0;
    for (int a = 0; a < 3; ++a) {
        const double stretch = std::fabs(component_of(d, a)) - values[3 + a];
        energy += 0.5 * values[a] * stretch * stretch;
    }
    return energy;
}

// K_a in [0.5, 20], r0_a in [0, 0.8]: the springs' rest lengths are about the bonds' components.
std::vector<double> spring_values(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> K(0.5, 20.0), r0(0.0, 0.8);
    return {K(rng), K(rng), K(rng), r0(rng), r0(rng), r0(rng)};
}

using Bond = HarmonicAnisotropicBond;
using Tether = FixedHarmonicAnisotropic;

ParamsOf<Bond> bond_params(const std::vector<double>& v) {
    return Bond::make_params<double>(values_in_order(Bond::parameters(), v.data()), kConstants);
}
ParamsOf<Tether> tether_params(const std::vector<double>& v) {
    return Tether::make_params<double>(values_in_order(Tether::parameters(), v.data()), kConstants);
}

// Random bonds, half of them straddling the box (random_chain's odd samples).
std::vector<Chain<2>> bonds(unsigned seed) {
    std::mt19937_64 rng(seed);
    std::vector<Chain<2>> chains;
    int straddling = 0;
    for (int sample = 0; sample < kSamples; ++sample) {
        chains.push_back(random_chain<2>(rng, sample));
        straddling += chains.back().straddles;
    }
    EXPECT_GT(straddling, kSamples / 5) << "too few bonds cross the boundary to test it";
    return chains;
}

TEST(HarmonicAnisotropicBond, ForceIsMinusGradientOfEnergy) {
    std::mt19937_64 rng(81);
    double worst = 0.0;
    for (const Chain<2>& c : bonds(1)) {
        const std::vector<double> v = spring_values(rng);
        const double error = finite_difference_error<Bond>(c.r, bond_params(v), 1e-3 * v[0]);
        EXPECT_LT(error, kForceTolerance);
        worst = std::max(worst, error);
    }
    report("HarmonicAnisotropicBond force vs finite differences", worst);
}

TEST(HarmonicAnisotropicBond, EnergyMatchesFormulaOfUnwrappedSeparation) {
    std::mt19937_64 rng(82);
    double worst = 0.0;
    for (const Chain<2>& c : bonds(2)) {
        const std::vector<double> v = spring_values(rng);
        V force[2];
        const double energy = Bond::compute(c.r, bond_params(v), kBox, force);
        const double expected = anisotropic_energy(v.data(), c.unwrapped[1] - c.unwrapped[0]);
        const double error = std::fabs(energy - expected) / std::max(expected, 1e-3 * v[0]);
        EXPECT_LT(error, 1e-9);
        worst = std::max(worst, error);
    }
    report("HarmonicAnisotropicBond energy vs formula", worst);
}

// U depends on |d_a|: swapping the particles, or mirroring one component of d, leaves U unchanged;
// the forces swap, or flip that component. The net force is zero (the term is not invariant under
// rotations, so the torque is not).
TEST(HarmonicAnisotropicBond, SymmetricInTheParticlesAndEachAxis) {
    std::mt19937_64 rng(83);
    for (const Chain<2>& c : bonds(3)) {
        const std::vector<double> v = spring_values(rng);
        const auto p = bond_params(v);
        V force[2], swapped_force[2];
        const double energy = Bond::compute(c.r, p, kBox, force);
        EXPECT_EQ(max_abs(force[0] + force[1]), 0.0);
        const V swapped[2] = {c.r[1], c.r[0]};
        EXPECT_NEAR(Bond::compute(swapped, p, kBox, swapped_force), energy, 1e-14 * (1.0 + energy));
        EXPECT_LT(max_abs(swapped_force[0] - force[1]), 1e-13 * (1.0 + max_abs(force[0])));
        for (int a = 0; a < 3; ++a) {
            V mirrored[2] = {c.r[0], c.r[1]};
            component(mirrored[1], a) = 2.0 * component_of(c.r[0], a) - component_of(c.r[1], a);
            V mirrored_force[2];
            EXPECT_NEAR(Bond::compute(mirrored, p, kBox, mirrored_force), energy, 1e-13 * (1.0 + energy));
            for (int b = 0; b < 3; ++b) {
                const double expected = (a == b ? -1.0 : 1.0) * component_of(force[1], b);
                EXPECT_NEAR(component_of(mirrored_force[1], b), expected, 1e-12 * (1.0 + max_abs(force[1])));
            }
        }
    }
}

// d_a = 0 with r0_a > 0: the spring of that axis is at its cusp, U has its value 1/2 K_a r0_a^2 and
// its force component is zero (the mean of the one-sided -+K_a r0_a), on either particle; the other
// axes are unaffected.
TEST(HarmonicAnisotropicBond, CuspAtZeroComponentHasNoForceAlongIt) {
    const std::vector<double> v = {4.0, 6.0, 8.0, 0.5, 0.3, 0.2};
    const V r[2] = {{0.1, -0.2, 0.3}, {0.1, 0.5, -0.1}};  // d = (0, 0.7, -0.4)
    V force[2];
    const double energy = Bond::compute(r, bond_params(v), kBox, force);
    EXPECT_DOUBLE_EQ(energy, anisotropic_energy(v.data(), V{0.0, 0.7, -0.4}));
    EXPECT_EQ(force[0].x, 0.0);
    EXPECT_EQ(force[1].x, 0.0);
    EXPECT_NEAR(force[0].y, 6.0 * (0.7 - 0.3), 1e-14);
    EXPECT_NEAR(force[0].z, -8.0 * (0.4 - 0.2), 1e-14);
    // The one-sided limits are the forces just off the cusp.
    for (const double side : {1.0, -1.0}) {
        V off[2] = {r[0], r[1]};
        off[1].x += side * 1e-12;
        V off_force[2];
        Bond::compute(off, bond_params(v), kBox, off_force);
        EXPECT_NEAR(off_force[1].x, side * 4.0 * 0.5, 1e-10);
    }
}

TEST(HarmonicAnisotropicBond, FloatAgreesWithDouble) {
    std::mt19937_64 rng(84);
    FloatAgreement worst{0, 0};
    for (const Chain<2>& c : bonds(4)) {
        const std::vector<double> v = spring_values(rng);
        const FloatAgreement a = float_agreement<Bond>(c.r, v.data(), 1e-2 * v[0], 1e-2 * v[0]);
        EXPECT_LT(a.energy, kFloatTolerance);
        EXPECT_LT(a.force, kFloatTolerance);
        worst = {std::max(worst.energy, a.energy), std::max(worst.force, a.force)};
    }
    report("HarmonicAnisotropicBond float vs double energy", worst.energy);
    report("HarmonicAnisotropicBond float vs double force", worst.force);
}

// ---- FixedHarmonicAnisotropic ----

// The separation from r to the nearest periodic image of point, by searching the 27 nearest images.
V nearest_image_separation(V point, V r) {
    V best{1e300, 0, 0};
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k) {
                const V d = point + V{i * kBox.length.x, j * kBox.length.y, k * kBox.length.z} - r;
                if (length(d) < length(best)) best = d;
            }
    return best;
}

// A wrapped particle position and values K, r0, point; half the points across a box face from the
// particle, so that the nearest image of the point lies across the boundary.
struct Tethered {
    V r[1];
    std::vector<double> values;
};

std::vector<Tethered> tethers(unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit_interval(0.0, 1.0);
    std::vector<Tethered> result;
    for (int sample = 0; sample < kSamples; ++sample) {
        V particle{(unit_interval(rng) - 0.5) * kBox.length.x, (unit_interval(rng) - 0.5) * kBox.length.y,
                   (unit_interval(rng) - 0.5) * kBox.length.z};
        V point = particle + (0.1 + 1.0 * unit_interval(rng)) * random_direction(rng);
        if (sample % 2 == 1) {
            particle.x = -0.5 * kBox.length.x + 0.2 * unit_interval(rng);
            point.x = 0.5 * kBox.length.x - 0.2 * unit_interval(rng);
        }
        std::vector<double> values = spring_values(rng);
        values.insert(values.end(), {point.x, point.y, point.z});
        result.push_back({{kBox.wrap(particle)}, values});
    }
    return result;
}

TEST(FixedHarmonicAnisotropic, ForceIsMinusGradientOfEnergy) {
    double worst = 0.0;
    for (const Tethered& t : tethers(91)) {
        const double error = finite_difference_error<Tether>(t.r, tether_params(t.values), 1e-3 * t.values[0]);
        EXPECT_LT(error, kForceTolerance);
        worst = std::max(worst, error);
    }
    report("FixedHarmonicAnisotropic force vs finite differences", worst);
}

TEST(FixedHarmonicAnisotropic, EnergyUsesTheNearestImageOfThePoint) {
    double worst = 0.0;
    int across = 0;
    for (const Tethered& t : tethers(92)) {
        V force[1];
        const double energy = Tether::compute(t.r, tether_params(t.values), kBox, force);
        const V point{t.values[6], t.values[7], t.values[8]};
        const V d = nearest_image_separation(point, t.r[0]);
        across += length(d) < length(point - t.r[0]) - 1e-9;
        const double expected = anisotropic_energy(t.values.data(), d);
        const double error = std::fabs(energy - expected) / std::max(expected, 1e-3 * t.values[0]);
        EXPECT_LT(error, 1e-9);
        worst = std::max(worst, error);
    }
    EXPECT_GT(across, kSamples / 5) << "too few points lie across the boundary to test it";
    report("FixedHarmonicAnisotropic energy vs formula", worst);
}

// The same springs as the bond whose first particle sits at the point: F_i is the bond's force on
// its second particle.
TEST(FixedHarmonicAnisotropic, IsTheBondToAParticleHeldAtThePoint) {
    for (const Tethered& t : tethers(94)) {
        const V point{t.values[6], t.values[7], t.values[8]};
        const V pair[2] = {t.r[0] + nearest_image_separation(point, t.r[0]), t.r[0]};
        V tether_force[1], bond_force[2];
        const double e_tether = Tether::compute(t.r, tether_params(t.values), kBox, tether_force);
        const double e_bond = Bond::compute(pair, bond_params(t.values), kBox, bond_force);
        EXPECT_NEAR(e_tether, e_bond, 1e-12 * (1.0 + e_bond));
        EXPECT_LT(max_abs(tether_force[0] - bond_force[1]), 1e-12 * (1.0 + max_abs(bond_force[1])));
    }
}

TEST(FixedHarmonicAnisotropic, PointOutsideTheBoxActsThroughItsImage) {
    const double inside[] = {3.0, 2.0, 1.0, 0.2, 0.1, 0.3, 0.4, -0.3, 0.9};
    const double outside[] = {3.0, 2.0, 1.0, 0.2, 0.1, 0.3,
                              0.4 + 2.0 * kBox.length.x, -0.3 - kBox.length.y, 0.9 + 3.0 * kBox.length.z};
    const V r[1] = {{-0.1, 0.2, 0.3}};
    V f_in[1], f_out[1];
    const double e_in = Tether::compute(r, tether_params({inside, inside + 9}), kBox, f_in);
    const double e_out = Tether::compute(r, tether_params({outside, outside + 9}), kBox, f_out);
    EXPECT_NEAR(e_out, e_in, 1e-12);
    EXPECT_LT(max_abs(f_out[0] - f_in[0]), 1e-12);
}

TEST(FixedHarmonicAnisotropic, ParticleOnThePoint) {
    const V r[1] = {{0.4, -0.3, 0.9}};
    V force[1];
    // r0 = 0: the minimum of U, no force.
    EXPECT_EQ(Tether::compute(r, tether_params({3.0, 2.0, 1.0, 0.0, 0.0, 0.0, 0.4, -0.3, 0.9}), kBox, force), 0.0);
    EXPECT_EQ(max_abs(force[0]), 0.0);
    // r0 > 0: every axis at its cusp; zero force, U = sum 1/2 K_a r0_a^2.
    EXPECT_DOUBLE_EQ(Tether::compute(r, tether_params({3.0, 2.0, 1.0, 0.5, 0.2, 0.1, 0.4, -0.3, 0.9}), kBox, force),
                     0.5 * (3.0 * 0.25 + 2.0 * 0.04 + 1.0 * 0.01));
    EXPECT_EQ(max_abs(force[0]), 0.0);
}

TEST(FixedHarmonicAnisotropic, FloatAgreesWithDouble) {
    FloatAgreement worst{0, 0};
    for (const Tethered& t : tethers(95)) {
        const FloatAgreement a = float_agreement<Tether>(t.r, t.values.data(), 1e-2 * t.values[0], 1e-2 * t.values[0]);
        EXPECT_LT(a.energy, kFloatTolerance);
        EXPECT_LT(a.force, kFloatTolerance);
        worst = {std::max(worst.energy, a.energy), std::max(worst.force, a.force)};
    }
    report("FixedHarmonicAnisotropic float vs double energy", worst.energy);
    report("FixedHarmonicAnisotropic float vs double force", worst.force);
}

}  // namespace
}  // namespace bonded_test
}  // namespace structmd
