// The five Expression components through the C API on the CPU backend: each against the built-in
// term it reproduces (1e-12 relative in double), forces against central differences of the energy,
// single and mixed precision, groups, startStep, energy terms and neighbour-list conditions, and
// the input errors of a bad expression.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "expression_scenes.hpp"

namespace structmd_expression_test {
namespace {

std::string bonds(const std::string& name, const std::string& cls, const std::string& subclass,
                  const std::string& labels, const std::string& data, const std::string& parameters = "") {
    return "\"" + name + "\": {\"type\": [\"" + cls + "\", \"" + subclass + "\"]" +
           (parameters.empty() ? "" : ", \"parameters\": {" + parameters + "}") + ", \"labels\": [" + labels +
           "], \"data\": " + data + "}";
}

const char* kMorseData = "[[0, 1, 1.0, 1.5, 0.8], [2, 3, 1.2, 0.9, 1.1], [4, 5, 0.9, 2.0, 0.6]]";
const char* kAngleData = "[[2, 3, 4, 40.0, 1.9], [3, 4, 5, 25.0, 2.4], [6, 2, 3, 10.0, 2.0]]";
const char* kDihedralData = "[[2, 3, 4, 5, 2, 3.0, 0.4], [6, 2, 3, 7, 3, 1.5, -1.0], [0, 1, 5, 4, 1, 2.0, 0.3]]";

struct Pairing {
    const char* what;
    std::string builtin;
    std::string expression;
    bool compareEnergy = true;
};

std::vector<Pairing> pairings() {
    const std::string morseLabels = "\"id_i\", \"id_j\", \"r0\", \"E\", \"D\"";
    const std::string angleLabels = "\"id_i\", \"id_j\", \"id_k\", \"K\", \"theta0\"";
    const std::string dihedralLabels = "\"id_i\", \"id_j\", \"id_k\", \"id_l\", \"n\", \"K\", \"phi0\"";
    return {
        {"LJ", neighbour_list() + ", " + builtin_lj("t", false), neighbour_list() + ", " + expression_lj("t", false)},
        {"LJ shifted", neighbour_list() + ", " + builtin_lj("t", true),
         neighbour_list() + ", " + expression_lj("t", true)},
        {"Morse", bonds("t", "Bond2", "Morse", morseLabels, kMorseData),
         bonds("t", "Bond2", "Expression", morseLabels, kMorseData,
               "\"energy\": \"E * ((1 - exp(-(r - r0) / D))^2 - 1)\"")},
        {"HarmonicAngular", bonds("t", "Bond3", "HarmonicAngular", angleLabels, kAngleData),
         bonds("t", "Bond3", "Expression", angleLabels, kAngleData, "\"energy\": \"0.5 * K * (theta - theta0)^2\"")},
        {"Dihedral", bonds("t", "Bond4", "Dihedral", dihedralLabels, kDihedralData),
         bonds("t", "Bond4", "Expression", dihedralLabels, kDihedralData,
               "\"energy\": \"K * (1 + cos(n * phi - phi0))\"")},
        {"Plates",
         "\"t\": {\"type\": [\"External\", \"Plates\"], \"parameters\": {\"platesSeparation\": 6.0, "
         "\"platesEpsilon\": 0.5, \"platesSigma\": 1.2}}",
         "\"t\": {\"type\": [\"External\", \"Expression\"], \"parameters\": {\"S\": 6.0, \"eps\": 0.5, \"sigma\": 1.2, "
         "\"energy\": \"eps * ((sigma / (S / 2 - z))^12 + (sigma / (z + S / 2))^12)\"}}"},
        {"ConstantForce",
         "\"t\": {\"type\": [\"External\", \"ConstantForce\"], \"parameters\": {\"constantForce\": [0.5, -1.25, 2.0]}}",
         "\"t\": {\"type\": [\"External\", \"Expression\"], \"parameters\": {\"energy\": \"-(0.5 * x - 1.25 * y + 2 * z)\"}}",
         false},  // the built-in field keeps no energy
    };
}

class AgainstBuiltin : public ::testing::TestWithParam<Pairing> {};

TEST_P(AgainstBuiltin, EnergyAndForcesAgreeInDouble) {
    const Pairing& p = GetParam();
    const Evaluation builtin = evaluate(p.builtin), expression = evaluate(p.expression);
    ASSERT_EQ(builtin.status, STRUCTMD_OK) << builtin.error;
    ASSERT_EQ(expression.status, STRUCTMD_OK) << expression.error;
    ASSERT_GT(max_abs(builtin.forces), 0.1) << "the term exerts no force here: the comparison would be empty";
    EXPECT_LT(max_relative_deviation(expression.forces, builtin.forces), 1e-12);
    if (p.compareEnergy) {
        ASSERT_NE(builtin.energy, 0.0);
        EXPECT_LT(relative_deviation(expression.energy, builtin.energy), 1e-12)
            << expression.energy << " vs " << builtin.energy;
    }
}

TEST_P(AgainstBuiltin, SingleAndMixedPrecisionAgreeToTheirRounding) {
    const Pairing& p = GetParam();
    for (const char* precision : {"single", "mixed"}) {
        SCOPED_TRACE(precision);
        const Evaluation builtin = evaluate(p.builtin, "potential", precision),
                         expression = evaluate(p.expression, "potential", precision);
        ASSERT_EQ(builtin.status, STRUCTMD_OK) << builtin.error;
        ASSERT_EQ(expression.status, STRUCTMD_OK) << expression.error;
        EXPECT_LT(max_relative_deviation(expression.forces, builtin.forces), 2e-5);
        if (p.compareEnergy) EXPECT_LT(relative_deviation(expression.energy, builtin.energy), 2e-5);
    }
}

INSTANTIATE_TEST_SUITE_P(Expression, AgainstBuiltin, ::testing::ValuesIn(pairings()),
                         [](const ::testing::TestParamInfo<Pairing>& info) {
                             std::string name = info.param.what;
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

// Forces against central differences of the energy, for expressions with no built-in twin; the
// pair 0-1 and the bond 0-1 straddle the periodic boundary.
TEST(ExpressionGradient, ForcesAreMinusTheGradientOfTheEnergy) {
    const std::vector<std::pair<const char*, std::string>> cases = {
        {"pair", neighbour_list() + ", \"t\": {\"type\": [\"NonBonded\", \"Expression\"], \"parameters\": {\"cutOff\": 2.2, "
                                    "\"condition\": \"all\", \"shift\": true, \"k\": 1.5, \"energy\": "
                                    "\"a * exp(-k * r^2) * cos(b * r) + c / r^3 + tanh(r - 1)\"}, "
                                    "\"labels\": [\"name_i\", \"name_j\", \"a\", \"b\", \"c\"], \"data\": "
                                    "[[\"A\", \"A\", 1.0, 2.0, 0.5], [\"A\", \"B\", -2.0, 1.5, 0.3], "
                                    "[\"B\", \"B\", 0.5, 3.0, 0.2]]}"},
        {"Bond2", bonds("t", "Bond2", "Expression", "\"id_i\", \"id_j\", \"k\"",
                        "[[0, 1, 2.0], [2, 3, 3.0], [4, 5, 1.5], [6, 7, 0.5]]",
                        "\"r0\": 1.1, \"energy\": \"k * (r - r0)^2 + log(1 + r^2) * sin(r)\"")},
        {"Bond3", bonds("t", "Bond3", "Expression", "\"id_i\", \"id_j\", \"id_k\"",
                        "[[2, 3, 4], [3, 4, 5], [1, 0, 9]]", "\"energy\": \"3 * (cos(theta) - cos(2))^2 + theta^3\"")},
        {"Bond4", bonds("t", "Bond4", "Expression", "\"id_i\", \"id_j\", \"id_k\", \"id_l\", \"w\"",
                        "[[2, 3, 4, 5, 1.0], [1, 0, 9, 7, 2.0]]",
                        "\"energy\": \"w * (1 + cos(2 * phi - 0.3)) + 0.2 * phi^2\"")},
        {"External", "\"t\": {\"type\": [\"External\", \"Expression\"], \"parameters\": {\"energy\": "
                     "\"0.1 * (x^2 + 2 * y^2) * exp(0.2 * z) + sin(x * y)\"}}"},
    };
    for (const auto& [what, forceField] : cases) {
        SCOPED_TRACE(what);
        Evaluation result;
        SimHandle sim = load(forceField, "cpu", "double", result);
        ASSERT_TRUE(sim) << result.error;
        const int64_t n = static_cast<int64_t>(positions().size());
        std::vector<double> x(3 * n), f(3 * n);
        for (int64_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) x[3 * i + k] = positions()[i][k];
        ASSERT_STRUCTMD_OK(sim.get(), structmd_get_forces(sim.get(), f.data(), n));
        ASSERT_GT(max_abs(f), 0.1);
        const double h = 1e-6;
        std::vector<double> numerical(3 * n);
        for (int64_t c = 0; c < 3 * n; ++c) {
            double energy[2];
            for (int side = 0; side < 2; ++side) {
                std::vector<double> moved = x;
                moved[c] += side == 0 ? h : -h;
                ASSERT_STRUCTMD_OK(sim.get(), structmd_set_positions(sim.get(), moved.data(), n));
                ASSERT_STRUCTMD_OK(sim.get(), structmd_get_energy(sim.get(), "potential", &energy[side]));
            }
            numerical[c] = -(energy[0] - energy[1]) / (2 * h);
        }
        EXPECT_LT(max_relative_deviation(f, numerical), 1e-6);
    }
}

// Groups, startStep, energy terms and the list's condition each change the result when honoured.
// The expression pair of `expression` computes what the built-in LJ of `builtin` does, and
// differs from the same pair acting on every particle pair of the list.
void expect_like_builtin_and_not_everyone(const std::string& builtin, const std::string& expression) {
    const Evaluation reference = evaluate(builtin), scoped = evaluate(expression);
    const Evaluation everyone = evaluate(neighbour_list() + ", " + expression_lj("t", false));
    ASSERT_EQ(scoped.status, STRUCTMD_OK) << scoped.error;
    EXPECT_LT(relative_deviation(scoped.energy, reference.energy), 1e-12);
    EXPECT_LT(max_relative_deviation(scoped.forces, reference.forces), 1e-12);
    EXPECT_GT(relative_deviation(everyone.energy, scoped.energy), 1e-3) << "the scope changes nothing";
}

TEST(ExpressionPairScope, TheGroupIsHonoured) {
    const std::string groups =
        "\"groups\": {\"type\": [\"Groups\", \"GroupsList\"], \"labels\": [\"name\", \"type\", \"selection\"], "
        "\"data\": [[\"g\", \"Ids\", [0, 1, 2, 3, 7]]]}, ";
    const std::string inGroup = ", \"group\": \"g\"";
    expect_like_builtin_and_not_everyone(groups + neighbour_list() + ", " + builtin_lj("t", false, inGroup),
                                         groups + neighbour_list() + ", " + expression_lj("t", false, inGroup));
}

TEST(ExpressionPairScope, StartStepAndEnergyTerms) {
    Evaluation result;
    SimHandle sim = load(neighbour_list() + ", " + expression_lj("late", false, ", \"startStep\": 1") + ", " +
                             builtin_lj("lj", false) + ", " + expression_lj("ljx", false),
                         "cpu", "double", result);
    ASSERT_TRUE(sim) << result.error;
    double late = -1, lj = 0, ljx = 0, total = 0;
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_energy(sim.get(), "late", &late));
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_energy(sim.get(), "lj", &lj));
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_energy(sim.get(), "ljx", &ljx));
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_energy(sim.get(), "potential", &total));
    EXPECT_EQ(late, 0.0) << "inactive before its startStep";
    EXPECT_LT(relative_deviation(ljx, lj), 1e-12);
    EXPECT_LT(relative_deviation(total, lj + ljx), 1e-12);
    ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), 1));
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_energy(sim.get(), "late", &late));
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_energy(sim.get(), "ljx", &ljx));
    EXPECT_LT(relative_deviation(late, ljx), 1e-12) << "active from step 1";
}

TEST(ExpressionPairScope, TheListConditionIsHonoured) {
    const std::string excluding =
        "\"nl\": {\"type\": [\"VerletConditionalListSet\", \"nonExcluded\"], \"parameters\": {\"cutOffVerletFactor\": 1.2}, "
        "\"labels\": [\"id\", \"id_list\"], \"data\": [[0, [1]], [1, [0]], [3, [4]], [4, [3]]]}";
    const auto swap_condition = [](std::string entry) {
        entry.replace(entry.find("\"condition\": \"all\""), 18, "\"condition\": \"nonExcluded\"");
        return entry;
    };
    expect_like_builtin_and_not_everyone(excluding + ", " + swap_condition(builtin_lj("t", false)),
                                         excluding + ", " + swap_condition(expression_lj("t", false)));
}

// Bad expressions are input errors that name the JSON path and, for the text, the column.
TEST(ExpressionInputErrors, EachNamesItsPath) {
    const std::string path = "topology.forceField.t.parameters.energy";
    const auto pair = [](const std::string& energy, const std::string& labels, const std::string& data,
                         const std::string& extra = "") {
        return neighbour_list() + ", \"t\": {\"type\": [\"NonBonded\", \"Expression\"], \"parameters\": {\"cutOff\": 2.5, "
               "\"condition\": \"all\", \"energy\": \"" + energy + "\"" + extra + "}, \"labels\": [\"name_i\", \"name_j\"" +
               labels + "], \"data\": [[\"A\", \"A\"" + data + "], [\"A\", \"B\"" + data + "], [\"B\", \"B\"" + data + "]]}";
    };
    struct Bad {
        const char* what;
        std::string forceField;
        std::string where;
        std::string says;
    };
    const std::vector<Bad> cases = {
        {"unparsable", pair("4 * e * (1 / r", ", \"e\"", ", 1.0"), path, "at column 15: expected ')'"},
        {"unknown variable", pair("e / r + q", ", \"e\"", ", 1.0"), path, "at column 9: unknown variable 'q'"},
        {"unknown function", pair("e * foo(r)", ", \"e\"", ", 1.0"), path, "at column 5: unknown function 'foo'"},
        {"missing data column", pair("e * s / r", ", \"e\"", ", 1.0"), path, "unknown variable 's'"},
        {"unused data column", pair("e / r", ", \"e\", \"s\"", ", 1.0, 2.0"), "topology.forceField.t.labels[3]",
         "the data column 's' is not used"},
        {"not finite at the cut-off", pair("e / (r - 2.5)", ", \"e\"", ", 1.0", ", \"shift\": true"), path,
         "not finite at the cut-off"},
        {"non-numeric parameter", pair("e * w / r", ", \"e\"", ", 1.0", ", \"w\": \"heavy\""),
         "topology.forceField.t.parameters.w", "expected"},
        {"not a text", neighbour_list() + ", \"t\": {\"type\": [\"NonBonded\", \"Expression\"], \"parameters\": "
                                          "{\"cutOff\": 2.5, \"condition\": \"all\", \"energy\": 3}}",
         path, "text expression"},
        {"no energy", "\"t\": {\"type\": [\"External\", \"Expression\"], \"parameters\": {\"k\": 1}}", path,
         "missing"},
        {"bond", bonds("t", "Bond3", "Expression", "\"id_i\", \"id_j\", \"id_k\"", "[[2, 3, 4]]",
                       "\"energy\": \"(theta - r)^2\""),
         path, "unknown variable 'r' (not theta"},
    };
    for (const Bad& bad : cases) {
        SCOPED_TRACE(bad.what);
        const Evaluation result = evaluate(bad.forceField);
        EXPECT_EQ(result.status, STRUCTMD_ERR_INPUT) << result.error;
        EXPECT_EQ(result.error.rfind(bad.where + ":", 0), 0u) << result.error;
        EXPECT_NE(result.error.find(bad.says), std::string::npos) << result.error;
    }
}

}  // namespace
}  // namespace structmd_expression_test
