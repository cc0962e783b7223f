// Dihedral, Dihedral4 and IdpFourierDihedral against finite differences of their energy, the IUPAC
// angle built by hand and by projection, the conservation laws and their float instantiation, and
// the collinear chain that has no dihedral.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "forcefield/dihedral.hpp"
#include "forcefield/idp_fourier_dihedral.hpp"

#include "bonded_test_support.hpp"

namespace structmd {
namespace bonded_test {
namespace {

// Parameter values per sample, in the order of the term's declared parameters: n, K, phi0 and K1..K4,
// phi0_1..phi0_4.
std::vector<double> dihedral_values(std::mt19937_64& rng) {
    std::uniform_int_distribution<int> n(1, 6);
    std::uniform_real_distribution<double> K(0.5, 10.0), phi0(-kPi, kPi);
    return {double(n(rng)), K(rng), phi0(rng)};
}
std::vector<double> dihedral4_values(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> K(-3.0, 5.0), phi0(-kPi, kPi);
    return {K(rng), K(rng), K(rng), K(rng), phi0(rng), phi0(rng), phi0(rng), phi0(rng)};
}

// U from the input-format formulas, with the angle computed here.
double dihedral_energy(const std::vector<double>& v, double phi) { return v[1] * (1.0 + std::cos(v[0] * phi - v[2])); }
double dihedral4_energy(const std::vector<double>& v, double phi) {
    double energy = 0.0;
    for (int n = 1; n <= 4; ++n) energy += v[n - 1] * (1.0 + std::cos(n * phi - v[3 + n]));
    return energy;
}

// The hand-built chain of IUPAC's definition: r1 at the origin, r2 on +z, r0 along +x, and r3 at
// angle `turn` from +x about +z, which is clockwise seen looking from r1 towards r2 (along +z) for a
// positive turn. It is then rotated and translated rigidly (a proper rotation keeps the sign).
void iupac_chain(double turn, V* r) {
    const V local[4] = {{1.2, 0.0, -0.3}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.1}, {0.9 * std::cos(turn), 0.9 * std::sin(turn), 1.5}};
    // Rotation by 0.7 rad about the unit axis (2, -1, 2)/3, by Rodrigues' formula.
    const V axis{2.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0};
    const double c = std::cos(0.7), s = std::sin(0.7);
    const V shift{0.4, -1.1, 0.6};
    for (int k = 0; k < 4; ++k) {
        const V v = local[k];
        r[k] = shift + (c * v + s * cross_product(axis, v) + ((1.0 - c) * dot(axis, v)) * axis);
    }
}

TEST(Dihedral, IupacSignConvention) {
    struct Case {
        double turn;
        double phi;  // the IUPAC dihedral of that chain
    };
    // cis, trans, and the clockwise (+90) and anticlockwise (-90) quarter turns.
    for (const Case& c : {Case{0.0, 0.0}, Case{kPi, kPi}, Case{0.5 * kPi, 0.5 * kPi}, Case{-0.5 * kPi, -0.5 * kPi}}) {
        V r[4];
        iupac_chain(c.turn, r);
        EXPECT_NEAR(std::cos(dihedral_by_projection(r[0], r[1], r[2], r[3]) - c.phi), 1.0, 1e-12) << c.turn;
        // U = 1 + cos(phi - phi0) takes 2 only at phi = phi0: probing phi0 = phi identifies the angle
        // and its sign through the energy alone.
        V force[4];
        const double probe[] = {1.0, 1.0, c.phi};
        EXPECT_NEAR(Dihedral::compute(r, Dihedral::make_params<double>(values_in_order(Dihedral::parameters(), probe), kConstants), kBox, force), 2.0, 1e-12)
            << "phi " << c.phi;
        const double opposite[] = {1.0, 1.0, c.phi + kPi};
        EXPECT_NEAR(Dihedral::compute(r, Dihedral::make_params<double>(values_in_order(Dihedral::parameters(), opposite), kConstants), kBox, force), 0.0, 1e-12)
            << "phi " << c.phi;
    }
    // +90 and -90 differ: U = 1 + sin(phi) (phi0 = pi/2) is 2 and 0.
    const double sine[] = {1.0, 1.0, 0.5 * kPi};
    V r[4], force[4];
    iupac_chain(0.5 * kPi, r);
    EXPECT_NEAR(Dihedral::compute(r, Dihedral::make_params<double>(values_in_order(Dihedral::parameters(), sine), kConstants), kBox, force), 2.0, 1e-12);
    iupac_chain(-0.5 * kPi, r);
    EXPECT_NEAR(Dihedral::compute(r, Dihedral::make_params<double>(values_in_order(Dihedral::parameters(), sine), kConstants), kBox, force), 0.0, 1e-12);
}

TEST(Dihedral, ForceIsMinusGradientOfEnergy) {
    std::mt19937_64 rng(31);
    double worst = 0.0;
    for (const Chain<4>& c : dihedral_chains(9)) {
        const std::vector<double> v = dihedral_values(rng);
        const double error =
            finite_difference_error<Dihedral>(c.r, Dihedral::make_params<double>(values_in_order(Dihedral::parameters(), v.data()), kConstants), 1e-3 * v[1]);
        EXPECT_LT(error, kForceTolerance);
        worst = std::max(worst, error);
    }
    report("Dihedral force vs finite differences", worst);
}

TEST(Dihedral, EnergyMatchesProjectedDihedral) {
    std::mt19937_64 rng(32);
    double worst = 0.0;
    for (const Chain<4>& c : dihedral_chains(10)) {
        const std::vector<double> v = dihedral_values(rng);
        V force[4];
        const double energy = Dihedral::compute(c.r, Dihedral::make_params<double>(values_in_order(Dihedral::parameters(), v.data()), kConstants), kBox, force);
        const double phi = dihedral_by_projection(c.unwrapped[0], c.unwrapped[1], c.unwrapped[2], c.unwrapped[3]);
        const double expected = dihedral_energy(v, phi);
        const double error = std::fabs(energy - expected) / std::max(expected, 1e-3 * v[1]);
        EXPECT_LT(error, 1e-8);
        worst = std::max(worst, error);
    }
    report("Dihedral energy vs formula", worst);
}

TEST(Dihedral, ForcesAndTorquesSumToZero) {
    std::mt19937_64 rng(33);
    Balance worst{0, 0};
    for (const Chain<4>& c : dihedral_chains(11)) {
        const std::vector<double> v = dihedral_values(rng);
        V force[4];
        Dihedral::compute(c.r, Dihedral::make_params<double>(values_in_order(Dihedral::parameters(), v.data()), kConstants), kBox, force);
        const Balance b = balance_of<4>(c.r, force);
        EXPECT_LT(b.net_force, kBalanceTolerance);
        EXPECT_LT(b.torque, kBalanceTolerance);
        worst = {std::max(worst.net_force, b.net_force), std::max(worst.torque, b.torque)};
    }
    report("Dihedral net force", worst.net_force);
    report("Dihedral net torque", worst.torque);
}

TEST(Dihedral, FloatAgreesWithDouble) {
    std::mt19937_64 rng(34);
    FloatAgreement worst{0, 0};
    for (const Chain<4>& c : dihedral_chains(12)) {
        const std::vector<double> v = dihedral_values(rng);
        const FloatAgreement a = float_agreement<Dihedral>(c.r, v.data(), 1e-3 * v[1], 1e-3 * v[1]);
        EXPECT_LT(a.energy, kFloatTolerance);
        EXPECT_LT(a.force, kFloatTolerance);
        worst = {std::max(worst.energy, a.energy), std::max(worst.force, a.force)};
    }
    report("Dihedral float vs double energy", worst.energy);
    report("Dihedral float vs double force", worst.force);
}

TEST(Dihedral, CollinearTripleFeelsNoForce) {
    const double values[] = {2.0, 3.0, 0.4};
    const auto p = Dihedral::make_params<double>(values_in_order(Dihedral::parameters(), values), kConstants);
    // r0, r1, r2 on a line; then r1, r2, r3 on a line.
    const V first[4] = {{-1.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {1.5, 0.8, 0.1}};
    const V second[4] = {{-0.5, 0.7, 0.2}, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {2.0, 0.0, 0.0}};
    for (const V* r : {first, second}) {
        V force[4];
        EXPECT_DOUBLE_EQ(Dihedral::compute(r, p, kBox, force), dihedral_energy({2.0, 3.0, 0.4}, 0.0));
        for (int k = 0; k < 4; ++k) EXPECT_EQ(max_abs(force[k]), 0.0);
    }
}

TEST(Dihedral4, ForceIsMinusGradientOfEnergy) {
    std::mt19937_64 rng(41);
    double worst = 0.0;
    for (const Chain<4>& c : dihedral_chains(13)) {
        const std::vector<double> v = dihedral4_values(rng);
        const double error =
            finite_difference_error<Dihedral4>(c.r, Dihedral4::make_params<double>(values_in_order(Dihedral4::parameters(), v.data()), kConstants), 1e-3);
        EXPECT_LT(error, kForceTolerance);
        worst = std::max(worst, error);
    }
    report("Dihedral4 force vs finite differences", worst);
}

TEST(Dihedral4, EnergyMatchesProjectedDihedral) {
    std::mt19937_64 rng(42);
    double worst = 0.0;
    for (const Chain<4>& c : dihedral_chains(14)) {
        const std::vector<double> v = dihedral4_values(rng);
        V force[4];
        const double energy = Dihedral4::compute(c.r, Dihedral4::make_params<double>(values_in_order(Dihedral4::parameters(), v.data()), kConstants), kBox, force);
        const double phi = dihedral_by_projection(c.unwrapped[0], c.unwrapped[1], c.unwrapped[2], c.unwrapped[3]);
        const double expected = dihedral4_energy(v, phi);
        const double error = std::fabs(energy - expected) / std::max(std::fabs(expected), 1e-3);
        EXPECT_LT(error, 1e-8);
        worst = std::max(worst, error);
    }
    report("Dihedral4 energy vs formula", worst);
}

// Dihedral4 with only the n-th term present is Dihedral with multiplicity n.
TEST(Dihedral4, EachTermIsTheDihedralOfThatMultiplicity) {
    const std::vector<Chain<4>> chains = dihedral_chains(15);
    for (int n = 1; n <= 4; ++n)
        for (int sample = 0; sample < 10; ++sample) {
            const Chain<4>& c = chains[sample];
            const double K = 1.0 + sample, phi0 = -kPi + 0.6 * sample;
            double four[8] = {0, 0, 0, 0, 0, 0, 0, 0};
            four[n - 1] = K;
            four[3 + n] = phi0;
            const double single[] = {double(n), K, phi0};
            V f4[4], f1[4];
            const double e4 = Dihedral4::compute(c.r, Dihedral4::make_params<double>(values_in_order(Dihedral4::parameters(), four), kConstants), kBox, f4);
            const double e1 = Dihedral::compute(c.r, Dihedral::make_params<double>(values_in_order(Dihedral::parameters(), single), kConstants), kBox, f1);
            EXPECT_NEAR(e4, e1, 1e-12 * K);
            for (int k = 0; k < 4; ++k) EXPECT_LT(max_abs(f4[k] - f1[k]), 1e-12 * K * (1.0 + max_abs(f1[k])));
        }
}

TEST(Dihedral4, ForcesAndTorquesSumToZero) {
    std::mt19937_64 rng(44);
    Balance worst{0, 0};
    for (const Chain<4>& c : dihedral_chains(16)) {
        const std::vector<double> v = dihedral4_values(rng);
        V force[4];
        Dihedral4::compute(c.r, Dihedral4::make_params<double>(values_in_order(Dihedral4::parameters(), v.data()), kConstants), kBox, force);
        const Balance b = balance_of<4>(c.r, force);
        EXPECT_LT(b.net_force, kBalanceTolerance);
        EXPECT_LT(b.torque, kBalanceTolerance);
        worst = {std::max(worst.net_force, b.net_force), std::max(worst.torque, b.torque)};
    }
    report("Dihedral4 net force", worst.net_force);
    report("Dihedral4 net torque", worst.torque);
}

TEST(Dihedral4, FloatAgreesWithDouble) {
    std::mt19937_64 rng(45);
    FloatAgreement worst{0, 0};
    for (const Chain<4>& c : dihedral_chains(17)) {
        const std::vector<double> v = dihedral4_values(rng);
        // Terms of either sign can cancel: the scales are those of the terms, sum |K_n| for U and
        // sum n |K_n| (times a unit lever arm) for F.
        double energy_scale = 0.0, force_scale = 0.0;
        for (int n = 1; n <= 4; ++n) {
            energy_scale += std::fabs(v[n - 1]);
            force_scale += n * std::fabs(v[n - 1]);
        }
        const FloatAgreement a = float_agreement<Dihedral4>(c.r, v.data(), energy_scale, force_scale);
        EXPECT_LT(a.energy, kFloatTolerance);
        EXPECT_LT(a.force, kFloatTolerance);
        worst = {std::max(worst.energy, a.energy), std::max(worst.force, a.force)};
    }
    report("Dihedral4 float vs double energy", worst.energy);
    report("Dihedral4 float vs double force", worst.force);
}

// ---- IdpFourierDihedral: no parameters, the paper's coefficients in units of k_B T ----

// KcalMol_A at 300 K: k_B T = 0.596 kcal/mol.
const Constants kRoomTemperature{1.987191e-3, 332.0716, 0.0, 300.0};
const double kRoomKT = 1.987191e-3 * 300.0;

// U of Smith, Ho and O'Hern as the input format writes it.
double idp_fourier_energy(double kT, double phi) {
    const double A[4] = {0.705, -0.313, -0.079, 0.041};
    const double B[4] = {-0.175, -0.093, 0.030, 0.030};
    double energy = 0.0;
    for (int s = 1; s <= 4; ++s) energy += A[s - 1] * std::cos(s * phi) + B[s - 1] * std::sin(s * phi);
    return kT * energy;
}

using Idp = IdpFourierDihedral;
ParamsOf<Idp> idp_params(const Constants& constants) {
    return Idp::make_params<double>(values_in_order(Idp::parameters(), nullptr), constants);
}

TEST(IdpFourierDihedral, ForceIsMinusGradientOfEnergy) {
    double worst = 0.0;
    for (const Chain<4>& c : dihedral_chains(71)) {
        const double error = finite_difference_error<Idp>(c.r, idp_params(kRoomTemperature), 1e-3 * kRoomKT);
        EXPECT_LT(error, kForceTolerance);
        worst = std::max(worst, error);
    }
    report("IdpFourierDihedral force vs finite differences", worst);
}

TEST(IdpFourierDihedral, EnergyMatchesProjectedDihedral) {
    double worst = 0.0;
    for (const Chain<4>& c : dihedral_chains(72)) {
        V force[4];
        const double energy = Idp::compute(c.r, idp_params(kRoomTemperature), kBox, force);
        const double phi = dihedral_by_projection(c.unwrapped[0], c.unwrapped[1], c.unwrapped[2], c.unwrapped[3]);
        const double expected = idp_fourier_energy(kRoomKT, phi);
        const double error = std::fabs(energy - expected) / std::max(std::fabs(expected), 1e-3 * kRoomKT);
        EXPECT_LT(error, 1e-8);
        worst = std::max(worst, error);
    }
    report("IdpFourierDihedral energy vs formula", worst);
}

// The sine terms tell +phi from -phi: on the hand-built IUPAC chains U(+90) = kT (B1 - A2 - B3 + A4)
// and U(-90) = kT (-B1 - A2 + B3 + A4), with cis and trans as checks of the cosine terms.
TEST(IdpFourierDihedral, IupacSignConvention) {
    struct Case {
        double turn;
        double expected_over_kT;
    };
    for (const Case& c : {Case{0.5 * kPi, -0.175 + 0.313 - 0.030 + 0.041}, Case{-0.5 * kPi, 0.175 + 0.313 + 0.030 + 0.041},
                          Case{0.0, 0.705 - 0.313 - 0.079 + 0.041}, Case{kPi, -0.705 - 0.313 + 0.079 + 0.041}}) {
        V r[4], force[4];
        iupac_chain(c.turn, r);
        EXPECT_NEAR(Idp::compute(r, idp_params(kRoomTemperature), kBox, force), c.expected_over_kT * kRoomKT, 1e-12)
            << "turn " << c.turn;
    }
}

// U is in units of k_B T: energies and forces scale with the temperature, and vanish at T = 0.
TEST(IdpFourierDihedral, ScalesWithTheTemperature) {
    const Chain<4> c = dihedral_chains(73)[0];
    Constants hot = kRoomTemperature, frozen = kRoomTemperature;
    hot.temperature = 600.0;
    frozen.temperature = 0.0;
    V f_room[4], f_hot[4], f_frozen[4];
    const double e_room = Idp::compute(c.r, idp_params(kRoomTemperature), kBox, f_room);
    const double e_hot = Idp::compute(c.r, idp_params(hot), kBox, f_hot);
    EXPECT_NEAR(e_hot, 2.0 * e_room, 1e-14 * kRoomKT);
    EXPECT_EQ(Idp::compute(c.r, idp_params(frozen), kBox, f_frozen), 0.0);
    for (int k = 0; k < 4; ++k) {
        EXPECT_LT(max_abs(f_hot[k] - 2.0 * f_room[k]), 1e-13 * kRoomKT * (1.0 + max_abs(f_room[k])));
        EXPECT_EQ(max_abs(f_frozen[k]), 0.0);
    }
}

TEST(IdpFourierDihedral, ForcesAndTorquesSumToZero) {
    Balance worst{0, 0};
    for (const Chain<4>& c : dihedral_chains(74)) {
        V force[4];
        Idp::compute(c.r, idp_params(kRoomTemperature), kBox, force);
        const Balance b = balance_of<4>(c.r, force);
        EXPECT_LT(b.net_force, kBalanceTolerance);
        EXPECT_LT(b.torque, kBalanceTolerance);
        worst = {std::max(worst.net_force, b.net_force), std::max(worst.torque, b.torque)};
    }
    report("IdpFourierDihedral net force", worst.net_force);
    report("IdpFourierDihedral net torque", worst.torque);
}

TEST(IdpFourierDihedral, FloatAgreesWithDouble) {
    FloatAgreement worst{0, 0};
    for (const Chain<4>& c : dihedral_chains(75)) {
        // The terms' scales, as for Dihedral4: kT sum |A_s|, |B_s| and kT sum s (|A_s| + |B_s|).
        const FloatAgreement a = float_agreement<Idp>(c.r, nullptr, 1.5 * kRoomKT, 3.0 * kRoomKT, kRoomTemperature);
        EXPECT_LT(a.energy, kFloatTolerance);
        EXPECT_LT(a.force, kFloatTolerance);
        worst = {std::max(worst.energy, a.energy), std::max(worst.force, a.force)};
    }
    report("IdpFourierDihedral float vs double energy", worst.energy);
    report("IdpFourierDihedral float vs double force", worst.force);
}

TEST(IdpFourierDihedral, CollinearTripleFeelsNoForce) {
    const V first[4] = {{-1.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {1.5, 0.8, 0.1}};
    const V second[4] = {{-0.5, 0.7, 0.2}, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {2.0, 0.0, 0.0}};
    for (const V* r : {first, second}) {
        V force[4];
        EXPECT_NEAR(Idp::compute(r, idp_params(kRoomTemperature), kBox, force), idp_fourier_energy(kRoomKT, 0.0),
                    1e-15);
        for (int k = 0; k < 4; ++k) EXPECT_EQ(max_abs(force[k]), 0.0);
    }
}

}  // namespace
}  // namespace bonded_test
}  // namespace structmd
