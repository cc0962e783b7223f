// Radial pair potentials, NonBonded and Bond2 forms: energies against the formulas of the input
// specification (written out here independently of the functors), U'(r)/r against a central finite
// difference of the functor's own energy, cutoffs, shifts, and single precision against double.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "forcefield/clashed.hpp"
#include "forcefield/debye_huckel.hpp"
#include "forcefield/dlvo.hpp"
#include "forcefield/gaussian_bond.hpp"
#include "forcefield/kim_hummer.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "forcefield/la_torre.hpp"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/lennard_jones_general.hpp"
#include "forcefield/lennard_jones_wca.hpp"
#include "forcefield/max_distance_restraint.hpp"
#include "forcefield/morse.hpp"
#include "forcefield/split_lennard_jones.hpp"
#include "forcefield/steric.hpp"
#include "forcefield/wca_core_wells.hpp"

using namespace structmd;

namespace {

constexpr double kEnergyTolerance = 1e-10;      // relative, double against the formula
constexpr double kDerivativeTolerance = 1e-6;   // relative, against the central difference
constexpr double kSinglePrecisionTolerance = 1e-4;  // relative, float against double

// The worst relative errors met, printed once all tests ran so that runs can be compared.
struct WorstErrors {
    double energy = 0.0;
    double derivative = 0.0;
    double single_precision = 0.0;
};
WorstErrors worst;

class PrintWorstErrors : public ::testing::Environment {
public:
    void TearDown() override {
        std::printf("worst relative errors: energy %.3g, U'(r)/r %.3g, float against double %.3g\n", worst.energy,
                    worst.derivative, worst.single_precision);
    }
};
::testing::Environment* const print_worst_errors = ::testing::AddGlobalTestEnvironment(new PrintWorstErrors);

double relative_error(double value, double reference) {
    return std::fabs(value - reference) / std::fabs(reference);
}

// The three Lennard-Jones shapes as the specification writes them, in epsilon, sigma and r.
double lj1(double eps, double s, double r) { return 4.0 * eps * (std::pow(s / r, 12) - std::pow(s / r, 6)); }
double lj2(double eps, double s, double r) { return eps * (std::pow(s / r, 12) - 2.0 * std::pow(s / r, 6)); }
double lj3(double eps, double s, double r) { return eps * (5.0 * std::pow(s / r, 12) - 6.0 * std::pow(s / r, 10)); }
using Formula = double (*)(double, double, double);

template <class Potential>
PairTerm<double> at(double r, const typename Potential::template Params<double>& p) {
    return Potential::evaluate(r * r, p);
}

// At each r: evaluate(r^2) gives U equal to `energy` and U'(r)/r equal to the central difference of
// its own energy.
void expect_term_matches(const std::function<PairTerm<double>(double)>& evaluate,
                         const std::function<double(double)>& energy, const std::vector<double>& radii) {
    for (const double r : radii) {
        SCOPED_TRACE("r = " + std::to_string(r));
        const PairTerm<double> term = evaluate(r * r);
        const double energy_error = relative_error(term.energy, energy(r));
        EXPECT_LT(energy_error, kEnergyTolerance) << term.energy << " against " << energy(r);
        const double h = 1e-6 * r;
        const double slope = (evaluate((r + h) * (r + h)).energy - evaluate((r - h) * (r - h)).energy) / (2.0 * h);
        const double derivative_error = relative_error(term.dudr_over_r, slope / r);
        EXPECT_LT(derivative_error, kDerivativeTolerance) << term.dudr_over_r << " against " << slope / r;
        worst.energy = std::max(worst.energy, energy_error);
        worst.derivative = std::max(worst.derivative, derivative_error);
    }
}

template <class Potential>
void expect_energy_and_derivative(const typename Potential::template Params<double>& p,
                                  const std::function<double(double)>& energy, const std::vector<double>& radii) {
    expect_term_matches([&](double r2) { return Potential::evaluate(r2, p); }, energy, radii);
}

template <class Potential>
void expect_no_interaction(const typename Potential::template Params<double>& p, const std::vector<double>& radii) {
    for (const double r : radii) {
        const PairTerm<double> term = at<Potential>(r, p);
        EXPECT_EQ(term.energy, 0.0) << "r = " << r;
        EXPECT_EQ(term.dudr_over_r, 0.0) << "r = " << r;
    }
}

// make(tag) builds the Params of the precision of tag; evaluate(r2, p) evaluates them. Energy and
// U'(r)/r in float agree with double.
template <class Make, class Evaluate>
void expect_float_matches_double(Make make, Evaluate evaluate, const std::vector<double>& radii) {
    const auto pd = make(double{});
    const auto pf = make(float{});
    for (const double r : radii) {
        SCOPED_TRACE("r = " + std::to_string(r));
        const PairTerm<double> d = evaluate(r * r, pd);
        const PairTerm<float> f = evaluate(float(r) * float(r), pf);
        const double energy_error = relative_error(f.energy, d.energy);
        const double derivative_error = relative_error(f.dudr_over_r, d.dudr_over_r);
        EXPECT_LT(energy_error, kSinglePrecisionTolerance);
        EXPECT_LT(derivative_error, kSinglePrecisionTolerance);
        worst.single_precision = std::max({worst.single_precision, energy_error, derivative_error});
    }
}

// A unit-free Lennard-Jones setup: sigma 1.3, epsilon 0.8, cutOffFactor 2.5.
constexpr double kEps = 0.8;
constexpr double kSigma = 1.3;
constexpr double kCutoff = 2.5 * kSigma;

// Radii in units of sigma inside 2.5 sigma, clear of the zeros of U and of U'.
std::vector<double> lennard_jones_radii() {
    std::vector<double> radii;
    for (const double x : {0.85, 0.95, 1.05, 1.3, 1.6, 2.0, 2.4}) radii.push_back(x * kSigma);
    return radii;
}

template <class Potential>
void check_cut_lennard_jones(Formula formula) {
    const auto p = Potential::template make_pair_params<double>(kEps, kSigma, kCutoff, false);
    expect_energy_and_derivative<Potential>(p, [&](double r) { return formula(kEps, kSigma, r); },
                                            lennard_jones_radii());
    // Not shifted, the energy jumps at the cutoff: just inside it is the full U(r_c).
    const double inside = kCutoff * (1.0 - 1e-9);
    EXPECT_NEAR(at<Potential>(inside, p).energy, formula(kEps, kSigma, kCutoff), 1e-9 * kEps);
    EXPECT_NE(formula(kEps, kSigma, kCutoff), 0.0);
    expect_no_interaction<Potential>(p, {kCutoff, kCutoff * (1.0 + 1e-9), 1.5 * kCutoff, 10.0 * kCutoff});
}

template <class Potential>
void check_shifted_lennard_jones(Formula formula) {
    const auto p = Potential::template make_pair_params<double>(kEps, kSigma, kCutoff, true);
    const double at_cutoff = formula(kEps, kSigma, kCutoff);
    expect_energy_and_derivative<Potential>(p, [&](double r) { return formula(kEps, kSigma, r) - at_cutoff; },
                                            lennard_jones_radii());
    EXPECT_NEAR(at<Potential>(kCutoff * (1.0 - 1e-9), p).energy, 0.0, 1e-9 * kEps);
    expect_no_interaction<Potential>(p, {kCutoff, 1.5 * kCutoff});
}

template <class Potential>
void check_bonded_lennard_jones(Formula formula) {
    const double values[] = {kEps, kSigma};
    const auto p = Potential::template make_bond_params<double>(values_in_order(Potential::bond_parameters(), values), Constants{});
    std::vector<double> radii = lennard_jones_radii();
    radii.push_back(3.0 * kSigma);  // beyond any NonBonded cutoff: a bond has none
    radii.push_back(40.0 * kSigma);
    expect_energy_and_derivative<Potential>(p, [&](double r) { return formula(kEps, kSigma, r); }, radii);
}

TEST(LennardJones, CutPairFormsMatchTheFormulas) {
    check_cut_lennard_jones<LennardJonesType1>(lj1);
    check_cut_lennard_jones<LennardJonesType2>(lj2);
    check_cut_lennard_jones<LennardJonesType3>(lj3);
}

TEST(LennardJones, ShiftSubtractsTheEnergyAtTheCutoff) {
    check_shifted_lennard_jones<LennardJonesType1>(lj1);
    check_shifted_lennard_jones<LennardJonesType2>(lj2);
    check_shifted_lennard_jones<LennardJonesType3>(lj3);
}

TEST(LennardJones, BondFormsHaveNoCutoff) {
    check_bonded_lennard_jones<LennardJonesType1>(lj1);
    check_bonded_lennard_jones<LennardJonesType2>(lj2);
    check_bonded_lennard_jones<LennardJonesType3>(lj3);
}

TEST(LennardJones, ShapesHaveTheirMinimumOfMinusEpsilonWhereDocumented) {
    const double r1 = std::pow(2.0, 1.0 / 6.0) * kSigma;
    const auto p1 = LennardJonesType1::make_pair_params<double>(kEps, kSigma, kCutoff, false);
    const auto p2 = LennardJonesType2::make_pair_params<double>(kEps, kSigma, kCutoff, false);
    const auto p3 = LennardJonesType3::make_pair_params<double>(kEps, kSigma, kCutoff, false);
    EXPECT_NEAR(at<LennardJonesType1>(r1, p1).energy, -kEps, 1e-14);
    EXPECT_NEAR(at<LennardJonesType2>(kSigma, p2).energy, -kEps, 1e-14);
    EXPECT_NEAR(at<LennardJonesType3>(kSigma, p3).energy, -kEps, 1e-14);
    EXPECT_NEAR(at<LennardJonesType1>(r1, p1).dudr_over_r, 0.0, 1e-13);
    EXPECT_NEAR(at<LennardJonesType2>(kSigma, p2).dudr_over_r, 0.0, 1e-13);
    EXPECT_NEAR(at<LennardJonesType3>(kSigma, p3).dudr_over_r, 0.0, 1e-13);
}

TEST(LennardJones, ZeroCutoffAndUnlistedPairsDoNotInteract) {
    for (const bool shifted : {false, true}) {
        const auto lennard_jones = LennardJonesType1::make_pair_params<double>(kEps, kSigma, 0.0, shifted);
        expect_no_interaction<LennardJonesType1>(lennard_jones, {0.5 * kSigma, kSigma});
        const auto wca = WCAType2::make_pair_params<double>(kEps, kSigma, 0.0, shifted);
        expect_no_interaction<WCAType2>(wca, {0.5 * kSigma});
    }
    expect_no_interaction<LennardJonesType3>(LennardJonesType3::Params<double>{}, {0.5 * kSigma, kSigma});
}

// WCA: the shape plus epsilon below its minimum r_min, zero beyond.
template <class Potential>
void check_wca(Formula formula, double r_min) {
    const auto p = Potential::template make_pair_params<double>(kEps, kSigma, kCutoff, false);
    std::vector<double> radii;
    for (const double x : {0.8, 0.85, 0.9, 0.95}) radii.push_back(x * kSigma);
    radii.push_back(0.98 * r_min);
    expect_energy_and_derivative<Potential>(p, [&](double r) { return formula(kEps, kSigma, r) + kEps; }, radii);
    // The cutoff that acts is r_min, not cutOffFactor x sigma.
    expect_no_interaction<Potential>(p, {r_min, r_min * (1.0 + 1e-9), 0.5 * (r_min + kCutoff), 0.99 * kCutoff});
    // Continuous at r_min, with a vanishing force.
    const PairTerm<double> inside = at<Potential>(r_min * (1.0 - 1e-8), p);
    EXPECT_NEAR(inside.energy, 0.0, 1e-12 * kEps);
    EXPECT_NEAR(inside.dudr_over_r, 0.0, 1e-5 * kEps / (kSigma * kSigma));
    // Shifting changes nothing when the cutoff lies beyond r_min: U(r_min) is already 0.
    const auto shifted = Potential::template make_pair_params<double>(kEps, kSigma, kCutoff, true);
    for (const double r : radii) EXPECT_NEAR(at<Potential>(r, shifted).energy, at<Potential>(r, p).energy, 1e-12);
}

TEST(WCA, ShapePlusEpsilonBelowTheMinimumAndZeroBeyond) {
    check_wca<WCAType1>(lj1, std::pow(2.0, 1.0 / 6.0) * kSigma);
    check_wca<WCAType2>(lj2, kSigma);
    check_wca<WCAType3>(lj3, kSigma);
}

TEST(WCA, Type1AddsTheFullEpsilon) {
    // At r = sigma the type-1 shape is 0, so WCAType1 is eps there (the reference's eps/4 would give eps/4).
    const auto p = WCAType1::make_pair_params<double>(kEps, kSigma, kCutoff, false);
    EXPECT_NEAR(at<WCAType1>(kSigma, p).energy, kEps, 1e-14);
}

TEST(WCA, CutoffShortOfTheMinimumCutsEarlier) {
    // cutOffFactor 1.05 < 2^(1/6) for type 1: the repulsion ends at 1.05 sigma.
    const double cutoff = 1.05 * kSigma;
    const auto p = WCAType1::make_pair_params<double>(kEps, kSigma, cutoff, false);
    expect_energy_and_derivative<WCAType1>(p, [](double r) { return lj1(kEps, kSigma, r) + kEps; },
                                           {0.9 * kSigma, 0.99 * kSigma, 1.04 * kSigma});
    expect_no_interaction<WCAType1>(p, {cutoff, 1.1 * kSigma});
    const auto shifted = WCAType1::make_pair_params<double>(kEps, kSigma, cutoff, true);
    const double at_cutoff = lj1(kEps, kSigma, cutoff);
    expect_energy_and_derivative<WCAType1>(shifted, [&](double r) { return lj1(kEps, kSigma, r) - at_cutoff; },
                                           {0.9 * kSigma, 0.95 * kSigma, 1.04 * kSigma});
    EXPECT_NEAR(at<WCAType1>(cutoff * (1.0 - 1e-12), shifted).energy, 0.0, 1e-10 * kEps);
}

template <class General, class WCA>
void check_general_positive_epsilon(Formula formula, double r_min) {
    for (const bool shifted : {false, true}) {
        const auto p = General::template make_pair_params<double>(kEps, kSigma, kCutoff, shifted);
        const auto wca = WCA::template make_pair_params<double>(kEps, kSigma, kCutoff, shifted);
        EXPECT_EQ(p.cutoff2, wca.cutoff2);
        expect_energy_and_derivative<General>(p, [&](double r) { return formula(kEps, kSigma, r) + kEps; },
                                              {0.85 * kSigma, 0.9 * kSigma, 0.97 * r_min});
        expect_no_interaction<General>(p, {r_min * (1.0 + 1e-9), 0.9 * kCutoff});
    }
}

template <class General>
void check_general_negative_epsilon(Formula formula) {
    const auto p = General::template make_pair_params<double>(-kEps, kSigma, kCutoff, false);
    expect_energy_and_derivative<General>(p, [&](double r) { return formula(kEps, kSigma, r); }, lennard_jones_radii());
    // The attractive well acts between r_min and r_c.
    EXPECT_LT(at<General>(1.6 * kSigma, p).energy, 0.0);
    expect_no_interaction<General>(p, {kCutoff, 1.2 * kCutoff});
    const auto shifted = General::template make_pair_params<double>(-kEps, kSigma, kCutoff, true);
    const double at_cutoff = formula(kEps, kSigma, kCutoff);
    expect_energy_and_derivative<General>(shifted, [&](double r) { return formula(kEps, kSigma, r) - at_cutoff; },
                                          lennard_jones_radii());
}

TEST(GeneralLennardJones, PositiveEpsilonIsTheWCAForm) {
    check_general_positive_epsilon<GeneralLennardJonesType1, WCAType1>(lj1, std::pow(2.0, 1.0 / 6.0) * kSigma);
    check_general_positive_epsilon<GeneralLennardJonesType2, WCAType2>(lj2, kSigma);
    check_general_positive_epsilon<GeneralLennardJonesType3, WCAType3>(lj3, kSigma);
}

TEST(GeneralLennardJones, NegativeEpsilonIsTheCutFormWithItsMagnitude) {
    check_general_negative_epsilon<GeneralLennardJonesType1>(lj1);
    check_general_negative_epsilon<GeneralLennardJonesType2>(lj2);
    check_general_negative_epsilon<GeneralLennardJonesType3>(lj3);
}

template <class Potential>
void check_steric(int n) {
    const auto formula = [n](double r) { return kEps * std::pow(kSigma / r, n); };
    const std::vector<double> radii{0.7 * kSigma, kSigma, 1.4 * kSigma, 2.3 * kSigma};
    const auto p = Potential::template make_pair_params<double>(kEps, kSigma, kCutoff, false);
    expect_energy_and_derivative<Potential>(p, formula, radii);
    expect_no_interaction<Potential>(p, {kCutoff, 1.3 * kCutoff});
    const auto shifted = Potential::template make_pair_params<double>(kEps, kSigma, kCutoff, true);
    expect_energy_and_derivative<Potential>(shifted, [&](double r) { return formula(r) - formula(kCutoff); }, radii);
    const double values[] = {kEps, kSigma};
    const auto bond = Potential::template make_bond_params<double>(values_in_order(Potential::bond_parameters(), values), Constants{});
    expect_energy_and_derivative<Potential>(bond, formula, {0.7 * kSigma, kSigma, 3.0 * kSigma, 20.0 * kSigma});
}

TEST(Steric, PairAndBondFormsMatchTheFormula) {
    check_steric<Steric6>(6);
    check_steric<Steric12>(12);
}

// Debye-Hueckel in kcal/mol and Angstrom: water-like dielectric, a 9 A Debye length.
const Constants kKcalMolA{1.987191e-3, 332.0716};
constexpr double kDielectric = 78.5;
constexpr double kDebyeLength = 9.0;
constexpr double kDebyeCutoff = 4.0 * kDebyeLength;

double debye_huckel(double charge_product, double r) {
    return 332.0716 * charge_product * std::exp(-r / kDebyeLength) / (kDielectric * r);
}

TEST(DebyeHuckel, UsesCharges) { EXPECT_TRUE(DebyeHuckel::uses_charges); }

TEST(DebyeHuckel, PairFormScalesWithTheChargeProduct) {
    const auto p = DebyeHuckel::make_params<double>(kDielectric, kDebyeLength, kDebyeCutoff, kKcalMolA);
    const std::vector<double> radii{1.5, 3.0, 7.0, 12.0, 25.0, 35.0};
    for (const double charge_product : {1.0, -0.42, 2.5}) {
        SCOPED_TRACE("q_i q_j = " + std::to_string(charge_product));
        for (const double r : radii) {
            const PairTerm<double> term = DebyeHuckel::evaluate(r * r, p, charge_product);
            const double expected = debye_huckel(charge_product, r);
            EXPECT_LT(relative_error(term.energy, expected), kEnergyTolerance);
            const double h = 1e-6 * r;
            const double slope = (DebyeHuckel::evaluate((r + h) * (r + h), p, charge_product).energy -
                                  DebyeHuckel::evaluate((r - h) * (r - h), p, charge_product).energy) /
                                 (2.0 * h);
            const double derivative_error = relative_error(term.dudr_over_r, slope / r);
            EXPECT_LT(derivative_error, kDerivativeTolerance);
            worst.energy = std::max(worst.energy, relative_error(term.energy, expected));
            worst.derivative = std::max(worst.derivative, derivative_error);
        }
        for (const double r : {kDebyeCutoff, 1.2 * kDebyeCutoff}) {
            const PairTerm<double> term = DebyeHuckel::evaluate(r * r, p, charge_product);
            EXPECT_EQ(term.energy, 0.0);
            EXPECT_EQ(term.dudr_over_r, 0.0);
        }
    }
    // Like charges repel: U'(r) < 0, so the force on i, U'(r)/r r_ij, points away from j.
    EXPECT_LT(DebyeHuckel::evaluate(9.0, p, 1.0).dudr_over_r, 0.0);
    EXPECT_GT(DebyeHuckel::evaluate(9.0, p, -1.0).dudr_over_r, 0.0);
}

TEST(DebyeHuckel, ShiftedPairFormReachesZeroAtTheCutoff) {
    const auto p = DebyeHuckel::make_params<double>(kDielectric, kDebyeLength, kDebyeCutoff, kKcalMolA, true);
    const double charge_product = -1.5;
    for (const double r : {2.0, 10.0, 30.0}) {
        const double expected = debye_huckel(charge_product, r) - debye_huckel(charge_product, kDebyeCutoff);
        EXPECT_LT(relative_error(DebyeHuckel::evaluate(r * r, p, charge_product).energy, expected), kEnergyTolerance);
    }
    const double inside = kDebyeCutoff * (1.0 - 1e-9);
    EXPECT_NEAR(DebyeHuckel::evaluate(inside * inside, p, charge_product).energy, 0.0, 1e-9);
}

TEST(DebyeHuckel, BondFormFoldsTheChargeProductIn) {
    const double charge_product = -0.8;
    const double bond_cutoff = 20.0;
    const double values[] = {charge_product, kDielectric, kDebyeLength, bond_cutoff};
    const auto p = DebyeHuckel::make_bond_params<double>(values_in_order(DebyeHuckel::bond_parameters(), values), kKcalMolA);
    expect_energy_and_derivative<DebyeHuckel>(p, [&](double r) { return debye_huckel(charge_product, r); },
                                              {1.0, 4.0, 9.0, 15.0, 19.5});
    expect_no_interaction<DebyeHuckel>(p, {bond_cutoff, 25.0});
}

TEST(Morse, MatchesTheFormula) {
    const double r0 = 1.5, depth = 2.2, width = 0.4;
    const double values[] = {r0, depth, width};
    const auto p = MorseBond::make_bond_params<double>(values_in_order(MorseBond::bond_parameters(), values), Constants{});
    const auto formula = [&](double r) {
        const double x = 1.0 - std::exp(-(r - r0) / width);
        return depth * (x * x - 1.0);
    };
    expect_energy_and_derivative<MorseBond>(p, formula, {0.9, 1.2, 1.4, 1.7, 2.3, 4.0});
    EXPECT_NEAR(at<MorseBond>(r0, p).energy, -depth, 1e-14);
    EXPECT_EQ(at<MorseBond>(0.0, p).dudr_over_r, 0.0);
}

TEST(Gaussian, MatchesTheFormula) {
    const double depth = 3.1, r0 = 2.0, variance = 0.3;
    const double values[] = {depth, r0, variance};
    const auto p = GaussianBond::make_bond_params<double>(values_in_order(GaussianBond::bond_parameters(), values), Constants{});
    const auto formula = [&](double r) { return -depth * std::exp(-(r - r0) * (r - r0) / (2.0 * variance)); };
    expect_energy_and_derivative<GaussianBond>(p, formula, {0.5, 1.2, 1.8, 2.3, 3.0, 4.5});
    EXPECT_NEAR(at<GaussianBond>(r0, p).energy, -depth, 1e-14);
    EXPECT_EQ(at<GaussianBond>(0.0, p).dudr_over_r, 0.0);
}

TEST(LennardJonesKaranicolasBrooks, BondMatchesTheFormulaWithItsMinimumAtSigma) {
    const double values[] = {kEps, kSigma};
    const auto p = LennardJonesKaranicolasBrooks::make_bond_params<double>(
        values_in_order(LennardJonesKaranicolasBrooks::bond_parameters(), values), Constants{});
    const auto formula = [&](double r) {
        const double x = kSigma / r;
        return kEps * (13.0 * std::pow(x, 12) - 18.0 * std::pow(x, 10) + 4.0 * std::pow(x, 6));
    };
    expect_energy_and_derivative<LennardJonesKaranicolasBrooks>(p, formula, {0.85, 0.95, 1.05, 1.45, 1.8, 4.0});
    EXPECT_NEAR(at<LennardJonesKaranicolasBrooks>(kSigma, p).energy, -kEps, 1e-13);
    EXPECT_NEAR(at<LennardJonesKaranicolasBrooks>(kSigma, p).dudr_over_r, 0.0, 1e-12);
}

// The WCA core as the specification writes it: eps [(s/r)^12 - 2 (s/r)^6] + eps below s, else 0.
double wca2(double eps, double s, double r) { return r < s ? lj2(eps, s, r) + eps : 0.0; }

TEST(MorseWCA, MorseWellPlusACoreEndingAtR0) {
    const double r0 = 1.2, depth = 2.0, width = 0.5, core = 3.0;
    const double values[] = {r0, depth, width, core};
    const auto p = MorseWCABond::make_bond_params<double>(values_in_order(MorseWCABond::bond_parameters(), values),
                                                          Constants{});
    const auto formula = [&](double r) {
        const double x = 1.0 - std::exp(-(r - r0) / width);
        return depth * (x * x - 1.0) + wca2(core, r0, r);
    };
    expect_energy_and_derivative<MorseWCABond>(p, formula, {0.8, 1.0, 1.15, 1.3, 1.7, 3.0});
    EXPECT_NEAR(at<MorseWCABond>(r0, p).energy, -depth, 1e-13);
}

TEST(LennardJonesGaussian, CorePlusAGaussianWellOfTheSameDepth) {
    const double variance = 0.2;
    const double values[] = {kEps, kSigma, variance};
    const auto p = LennardJonesGaussianBond::make_bond_params<double>(
        values_in_order(LennardJonesGaussianBond::bond_parameters(), values), Constants{});
    const auto formula = [&](double r) {
        return wca2(kEps, kSigma, r) - kEps * std::exp(-(r - kSigma) * (r - kSigma) / (2.0 * variance));
    };
    expect_energy_and_derivative<LennardJonesGaussianBond>(p, formula, {0.9, 1.1, 1.25, 1.35, 1.6, 2.5, 3.5});
    EXPECT_NEAR(at<LennardJonesGaussianBond>(kSigma, p).energy, -kEps, 1e-13);
}

TEST(MaxDistanceRestraint, FreeUpToTheLargestDistanceHarmonicBeyond) {
    const double K = 12.0, largest = 1.7;
    const double values[] = {K, largest};
    const auto p = MaxDistanceRestraint::make_bond_params<double>(
        values_in_order(MaxDistanceRestraint::bond_parameters(), values), Constants{});
    expect_energy_and_derivative<MaxDistanceRestraint>(
        p, [&](double r) { return 0.5 * K * (r - largest) * (r - largest); }, {1.75, 2.0, 3.0, 8.0});
    expect_no_interaction<MaxDistanceRestraint>(p, {0.0, 0.5, 1.0, 1.69, largest});
    // U and U' continuous at maxDistance: just beyond it both are of the order of the step.
    const PairTerm<double> beyond = at<MaxDistanceRestraint>(largest * (1.0 + 1e-9), p);
    EXPECT_LT(beyond.energy, 1e-15 * K);
    EXPECT_LT(beyond.dudr_over_r * largest, 1e-7 * K);
    EXPECT_GT(beyond.dudr_over_r, 0.0);
}

// maxDistance = 0 leaves the bond a harmonic spring of rest length 0, zero force at r = 0 included.
TEST(MaxDistanceRestraint, ZeroDistanceIsTheHarmonicBondOfRestLengthZero) {
    const double restraint_values[] = {12.0, 0.0}, harmonic_values[] = {12.0, 0.0};
    const auto restraint = MaxDistanceRestraint::make_bond_params<double>(
        values_in_order(MaxDistanceRestraint::bond_parameters(), restraint_values), Constants{});
    const auto harmonic =
        HarmonicBond::make_bond_params<double>(values_in_order(HarmonicBond::bond_parameters(), harmonic_values), Constants{});
    for (const double r : {0.0, 0.3, 1.0, 4.0}) {
        const PairTerm<double> a = at<MaxDistanceRestraint>(r, restraint), b = at<HarmonicBond>(r, harmonic);
        EXPECT_DOUBLE_EQ(a.energy, b.energy) << "r = " << r;
        EXPECT_DOUBLE_EQ(a.dudr_over_r, b.dudr_over_r) << "r = " << r;
    }
}

template <class Potential>
void check_single_precision_pair(double epsilon, const std::vector<double>& radii) {
    expect_float_matches_double(
        [&](auto tag) { return Potential::template make_pair_params<decltype(tag)>(epsilon, kSigma, kCutoff, false); },
        [](auto r2, const auto& p) { return Potential::evaluate(r2, p); }, radii);
}

template <class Potential>
void check_single_precision_bond(std::vector<double> values, const std::vector<double>& radii) {
    expect_float_matches_double(
        [&](auto tag) { return Potential::template make_bond_params<decltype(tag)>(values_in_order(Potential::bond_parameters(), values.data()), kKcalMolA); },
        [](auto r2, const auto& p) { return Potential::evaluate(r2, p); }, radii);
}

TEST(SinglePrecision, MatchesDouble) {
    const std::vector<double> radii = lennard_jones_radii();
    const std::vector<double> repulsive{0.8 * kSigma, 0.9 * kSigma, 0.95 * kSigma};
    check_single_precision_pair<LennardJonesType1>(kEps, radii);
    check_single_precision_pair<LennardJonesType2>(kEps, radii);
    check_single_precision_pair<LennardJonesType3>(kEps, radii);
    check_single_precision_pair<WCAType1>(kEps, repulsive);
    check_single_precision_pair<WCAType2>(kEps, repulsive);
    check_single_precision_pair<WCAType3>(kEps, repulsive);
    check_single_precision_pair<GeneralLennardJonesType1>(kEps, repulsive);
    check_single_precision_pair<GeneralLennardJonesType2>(-kEps, radii);
    check_single_precision_pair<GeneralLennardJonesType3>(-kEps, radii);
    check_single_precision_pair<Steric6>(kEps, radii);
    check_single_precision_pair<Steric12>(kEps, radii);
    check_single_precision_bond<LennardJonesType1>({kEps, kSigma}, {0.9, 1.4, 5.0});
    check_single_precision_bond<Steric12>({kEps, kSigma}, {0.9, 1.4, 5.0});
    check_single_precision_bond<DebyeHuckel>({-0.8, kDielectric, kDebyeLength, 20.0}, {1.0, 4.0, 15.0});
    check_single_precision_bond<MorseBond>({1.5, 2.2, 0.4}, {0.9, 1.2, 1.7, 2.3});
    check_single_precision_bond<GaussianBond>({3.1, 2.0, 0.3}, {0.5, 1.2, 2.3, 3.0});
    check_single_precision_bond<MaxDistanceRestraint>({12.0, 1.7}, {1.9, 2.3, 3.0, 8.0});
    check_single_precision_bond<LennardJonesKaranicolasBrooks>({kEps, kSigma}, {0.9, 1.05, 1.4, 3.0});
    check_single_precision_bond<MorseWCABond>({1.2, 2.0, 0.5, 3.0}, {0.9, 1.1, 1.5, 2.5});
    check_single_precision_bond<LennardJonesGaussianBond>({kEps, kSigma, 0.2}, {0.9, 1.1, 1.5, 2.5});
    expect_float_matches_double(
        [](auto tag) {
            return DebyeHuckel::make_params<decltype(tag)>(kDielectric, kDebyeLength, kDebyeCutoff, kKcalMolA);
        },
        [](auto r2, const auto& p) { return DebyeHuckel::evaluate(r2, p, decltype(r2)(-0.42)); },
        {1.5, 7.0, 25.0});
}

// Named values, as the reader gives a potential its entry's and row's parameters.
ParameterValues named(std::initializer_list<std::pair<const char*, double>> values) {
    ParameterValues v;
    for (const auto& [name, value] : values) v.set(name, {value});
    return v;
}

// Split Lennard-Jones, written out: eps_r below 2^(1/6) s, epsilon_a x epsilon beyond.
constexpr double kRepulsiveEpsilon = 1.7, kAttractiveFactor = 0.6;
double split_lennard_jones(double r) {
    const double attractive = kAttractiveFactor * kEps;
    if (r < std::pow(2.0, 1.0 / 6.0) * kSigma) return lj1(kRepulsiveEpsilon, kSigma, r) + kRepulsiveEpsilon - attractive;
    return lj1(attractive, kSigma, r);
}

SplitLennardJones::Params<double> split_params(bool shift) {
    return SplitLennardJones::make_pair_params<double>(
        named({{"epsilon", kEps}, {"sigma", kSigma}, {"epsilon_r", kRepulsiveEpsilon}, {"epsilon_a", kAttractiveFactor}}),
        Constants{}, 2.5, shift);
}

TEST(SplitLennardJones, RepulsiveAndAttractiveScalesMatchTheFormula) {
    const auto p = split_params(false);
    expect_energy_and_derivative<SplitLennardJones>(p, split_lennard_jones, lennard_jones_radii());
    // Continuous at r_min, where both sides are the well's bottom -epsilon_a x epsilon.
    const double r_min = std::pow(2.0, 1.0 / 6.0) * kSigma;
    for (const double r : {r_min * (1.0 - 1e-9), r_min * (1.0 + 1e-9)}) {
        EXPECT_NEAR(at<SplitLennardJones>(r, p).energy, -kAttractiveFactor * kEps, 1e-7);
        EXPECT_NEAR(at<SplitLennardJones>(r, p).dudr_over_r, 0.0, 1e-6);
    }
    expect_no_interaction<SplitLennardJones>(p, {kCutoff, 1.5 * kCutoff});
    const auto shifted = split_params(true);
    expect_energy_and_derivative<SplitLennardJones>(
        shifted, [](double r) { return split_lennard_jones(r) - split_lennard_jones(kCutoff); }, lennard_jones_radii());
}

// LaTorre, written out.
constexpr double kWidth = 0.7;
double la_torre(double r) {
    const double r_min = std::pow(2.0, 1.0 / 6.0) * kSigma;
    if (r <= r_min) return -kEps;
    if (r >= r_min + kWidth) return 0.0;
    const double c = std::cos(M_PI * (r - r_min) / (2.0 * kWidth));
    return -kEps * c * c;
}

TEST(LaTorre, FlatWellFadingOverItsWidth) {
    const auto p = LaTorre::make_pair_params<double>(named({{"epsilon", kEps}, {"sigma", kSigma}, {"w", kWidth}}),
                                                     Constants{}, 0.0, false);
    const double r_min = std::pow(2.0, 1.0 / 6.0) * kSigma;
    expect_energy_and_derivative<LaTorre>(p, la_torre, {r_min + 0.1 * kWidth, r_min + 0.45 * kWidth,
                                                        r_min + 0.8 * kWidth, r_min + 0.97 * kWidth});
    for (const double r : {0.8 * kSigma, r_min}) {
        EXPECT_EQ(at<LaTorre>(r, p).energy, -kEps);
        EXPECT_EQ(at<LaTorre>(r, p).dudr_over_r, 0.0);
    }
    EXPECT_NEAR(std::sqrt(p.cutoff2), r_min + kWidth, 1e-12);
    expect_no_interaction<LaTorre>(p, {r_min + kWidth, 2.0 * (r_min + kWidth)});
}

TEST(Clashed, SoftRepulsionOfOverlappingRadii) {
    EXPECT_TRUE(Clashed::uses_radii);
    const double lambda = 3.0, gamma = 1.2, a_i = 0.4, a_j = 0.7;
    Constants constants;
    constants.largestRadius = 0.9;
    const auto p = Clashed::make_pair_params<double>(named({{"lambda", lambda}, {"gamma", gamma}}), constants, 0.0,
                                                     false);
    EXPECT_NEAR(std::sqrt(p.cutoff2), 2.0 * gamma * 0.9, 1e-12);
    const double d = gamma * (a_i + a_j);
    const auto evaluate = [&](double r2) { return Clashed::evaluate(r2, p, a_i, a_j); };
    expect_term_matches(evaluate, [&](double r) { return lambda * (d * d - r * r) * (d * d - r * r); },
                        {0.2 * d, 0.5 * d, 0.8 * d, 0.99 * d});
    for (const double r : {d, 1.01 * d, 1.9 * d}) {
        EXPECT_EQ(evaluate(r * r).energy, 0.0);
        EXPECT_EQ(evaluate(r * r).dudr_over_r, 0.0);
    }
}

// DLVO, written out: Lennard-Jones of the row plus the electrostatics of two charged spheres.
constexpr double kRadiusI = 1.5, kRadiusJ = 2.5;
double charged_spheres(double charge_product, double r) {
    return 332.0716 * charge_product * std::exp(-(r - kRadiusI - kRadiusJ) / kDebyeLength) /
           (kDielectric * r * (1.0 + kRadiusI / kDebyeLength) * (1.0 + kRadiusJ / kDebyeLength));
}

ParameterValues dlvo_values() {
    return named({{"epsilon", kEps}, {"sigma", kSigma}, {"cutOffNPFactor", 2.5}, {"cutOffDHFactor", 4.0},
                  {"dielectricConstant", kDielectric}, {"debyeLength", kDebyeLength}});
}

template <class Potential>
void check_dlvo(Formula lennard_jones) {
    EXPECT_TRUE(Potential::uses_charges && Potential::uses_radii);
    const double charge_product = -0.7;
    const auto evaluate_with = [&](const auto& p) {
        return [&p, charge_product](double r2) { return Potential::evaluate(r2, p, charge_product, kRadiusI, kRadiusJ); };
    };
    const auto p = Potential::template make_pair_params<double>(dlvo_values(), kKcalMolA, 0.0, false);
    EXPECT_NEAR(std::sqrt(p.cutoff2), kDebyeCutoff, 1e-12);
    const auto both = [&](double r) {
        return (r < kCutoff ? lennard_jones(kEps, kSigma, r) : 0.0) + charged_spheres(charge_product, r);
    };
    std::vector<double> radii = lennard_jones_radii();
    radii.insert(radii.end(), {6.0, 20.0, 35.0});
    expect_term_matches(evaluate_with(p), both, radii);
    // An unlisted type pair keeps the electrostatics only.
    const auto unlisted = Potential::template make_unlisted_pair_params<double>(dlvo_values(), kKcalMolA, 0.0, false);
    expect_term_matches(evaluate_with(unlisted), [&](double r) { return charged_spheres(charge_product, r); },
                        {1.2, 3.0, 20.0});
    // Shifted, each term reaches 0 at its own cutoff.
    const auto shifted = Potential::template make_pair_params<double>(dlvo_values(), kKcalMolA, 0.0, true);
    const auto both_shifted = [&](double r) {
        return (r < kCutoff ? lennard_jones(kEps, kSigma, r) - lennard_jones(kEps, kSigma, kCutoff) : 0.0) +
               charged_spheres(charge_product, r) - charged_spheres(charge_product, kDebyeCutoff);
    };
    expect_term_matches(evaluate_with(shifted), both_shifted, radii);
    for (const double r : {kDebyeCutoff, 1.2 * kDebyeCutoff}) {
        EXPECT_EQ(evaluate_with(p)(r * r).energy, 0.0);
        EXPECT_EQ(evaluate_with(p)(r * r).dudr_over_r, 0.0);
    }
}

TEST(DLVO, LennardJonesPlusChargedSpheres) {
    check_dlvo<DLVOType1>(lj1);
    check_dlvo<DLVOType2>(lj2);
    check_dlvo<DLVOType3>(lj3);
}

// Kim-Hummer's contact term, written out from the paper.
double kim_hummer_contact(double epsilon, double zero_energy, double r) {
    if (epsilon == 0.0) return zero_energy * std::pow(kSigma / r, 12);
    if (epsilon < 0.0) return lj1(-epsilon, kSigma, r);
    if (r < std::pow(2.0, 1.0 / 6.0) * kSigma) return lj1(epsilon, kSigma, r) + 2.0 * epsilon;
    return -lj1(epsilon, kSigma, r);
}

ParameterValues kim_hummer_values(double epsilon) {
    return named({{"epsilon", epsilon}, {"sigma", kSigma}, {"cutOffNPFactor", 2.5}, {"cutOffDHFactor", 4.0},
                  {"dielectricConstant", kDielectric}, {"debyeLength", kDebyeLength}, {"zeroEnergy", 0.3}});
}

TEST(KimHummer, ContactFormsByTheSignOfEpsilonPlusDebyeHuckel) {
    EXPECT_TRUE(KimHummer::uses_charges);
    const double charge_product = 0.9;
    std::vector<double> radii = lennard_jones_radii();
    radii.insert(radii.end(), {6.0, 20.0, 35.0});
    for (const double epsilon : {-kEps, kEps, 0.0}) {
        SCOPED_TRACE("epsilon = " + std::to_string(epsilon));
        for (const bool shift : {false, true}) {
            const auto p = KimHummer::make_pair_params<double>(kim_hummer_values(epsilon), kKcalMolA, 0.0, shift);
            const auto formula = [&](double r) {
                const double at_cutoff = shift ? kim_hummer_contact(epsilon, 0.3, kCutoff) : 0.0;
                const double dh_at_cutoff = shift ? debye_huckel(charge_product, kDebyeCutoff) : 0.0;
                return (r < kCutoff ? kim_hummer_contact(epsilon, 0.3, r) - at_cutoff : 0.0) +
                       debye_huckel(charge_product, r) - dh_at_cutoff;
            };
            expect_term_matches([&](double r2) { return KimHummer::evaluate(r2, p, charge_product); }, formula, radii);
        }
    }
    // The repulsive form is continuous at r_0 = 2^(1/6) s, where it is +epsilon.
    const auto p = KimHummer::make_pair_params<double>(kim_hummer_values(kEps), Constants{}, 0.0, false);
    const double r0 = std::pow(2.0, 1.0 / 6.0) * kSigma;
    for (const double r : {r0 * (1.0 - 1e-9), r0 * (1.0 + 1e-9)})
        EXPECT_NEAR(KimHummer::evaluate(r * r, p, 0.0).energy, kEps, 1e-7);
    // An unlisted type pair keeps the electrostatics only.
    const auto unlisted = KimHummer::make_unlisted_pair_params<double>(kim_hummer_values(kEps), kKcalMolA, 0.0, false);
    expect_term_matches([&](double r2) { return KimHummer::evaluate(r2, unlisted, charge_product); },
                        [&](double r) { return debye_huckel(charge_product, r); }, {1.2, 3.0, 20.0});
}

TEST(SinglePrecision, NewPairPotentialsMatchDouble) {
    const std::vector<double> radii = lennard_jones_radii();
    expect_float_matches_double(
        [](auto tag) {
            return SplitLennardJones::make_pair_params<decltype(tag)>(
                named({{"epsilon", kEps}, {"sigma", kSigma}, {"epsilon_r", 1.7}, {"epsilon_a", 0.6}}), Constants{}, 2.5,
                false);
        },
        [](auto r2, const auto& p) { return SplitLennardJones::evaluate(r2, p); }, radii);
    expect_float_matches_double(
        [](auto tag) {
            return LaTorre::make_pair_params<decltype(tag)>(named({{"epsilon", kEps}, {"sigma", kSigma}, {"w", kWidth}}),
                                                            Constants{}, 0.0, false);
        },
        [](auto r2, const auto& p) { return LaTorre::evaluate(r2, p); }, {1.5, 1.7, 1.9});
    expect_float_matches_double(
        [](auto tag) {
            Constants c;
            c.largestRadius = 0.9;
            return Clashed::make_pair_params<decltype(tag)>(named({{"lambda", 3.0}, {"gamma", 1.2}}), c, 0.0, false);
        },
        [](auto r2, const auto& p) {
            using R = decltype(r2);
            return Clashed::evaluate(r2, p, R(0.4), R(0.7));
        },
        {0.3, 0.6, 1.0});
    expect_float_matches_double(
        [](auto tag) { return DLVOType1::make_pair_params<decltype(tag)>(dlvo_values(), kKcalMolA, 0.0, false); },
        [](auto r2, const auto& p) {
            using R = decltype(r2);
            return DLVOType1::evaluate(r2, p, R(-0.7), R(kRadiusI), R(kRadiusJ));
        },
        {1.2, 1.4, 6.0, 20.0});
    for (const double epsilon : {-kEps, kEps, 0.0})
        expect_float_matches_double(
            [&](auto tag) {
                return KimHummer::make_pair_params<decltype(tag)>(kim_hummer_values(epsilon), kKcalMolA, 0.0, false);
            },
            [](auto r2, const auto& p) { return KimHummer::evaluate(r2, p, decltype(r2)(0.9)); }, {1.2, 1.4, 6.0, 20.0});
}

}  // namespace
