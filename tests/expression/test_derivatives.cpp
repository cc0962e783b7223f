// Every function's value and derivative through the bytecode against its analytic value, the
// rules at kinks, and derivatives that depend on a column or another input.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "expression_test_support.hpp"

namespace structmd::expression::test {
namespace {

struct Case {
    const char* text;
    double x;
    double value;
    double slope;
};

TEST(ExpressionDerivatives, EachFunctionAgainstItsAnalyticDerivative) {
    const double x = 0.37;
    const Case cases[] = {
        {"sqrt(x)", x, std::sqrt(x), 0.5 / std::sqrt(x)},
        {"exp(x)", x, std::exp(x), std::exp(x)},
        {"log(x)", x, std::log(x), 1.0 / x},
        {"sin(x)", x, std::sin(x), std::cos(x)},
        {"cos(x)", x, std::cos(x), -std::sin(x)},
        {"tan(x)", x, std::tan(x), 1.0 / (std::cos(x) * std::cos(x))},
        {"acos(x)", x, std::acos(x), -1.0 / std::sqrt(1 - x * x)},
        {"asin(x)", x, std::asin(x), 1.0 / std::sqrt(1 - x * x)},
        {"atan(x)", x, std::atan(x), 1.0 / (1 + x * x)},
        {"tanh(x)", x, std::tanh(x), 1.0 / (std::cosh(x) * std::cosh(x))},
        {"cosh(x)", x, std::cosh(x), std::sinh(x)},
        {"sinh(x)", x, std::sinh(x), std::cosh(x)},
        {"abs(x)", x, x, 1.0},
        {"abs(x)", -x, x, -1.0},
        {"min(x, 0.5)", x, x, 1.0},
        {"min(x, 0.2)", x, 0.2, 0.0},
        {"max(x, 0.5)", x, 0.5, 0.0},
        {"max(2 * x, 0.5)", x, 2 * x, 2.0},
        {"step(x - 0.3)", x, 1.0, 0.0},
        {"step(x - 0.4)", x, 0.0, 0.0},
        {"pow(x, 3)", x, x * x * x, 3 * x * x},
        {"pow(x, 2.5)", x, std::pow(x, 2.5), 2.5 * std::pow(x, 1.5)},
        {"pow(2, x)", x, std::pow(2.0, x), std::log(2.0) * std::pow(2.0, x)},
        {"x^x", x, std::pow(x, x), std::pow(x, x) * (std::log(x) + 1)},
        {"x^-3", x, std::pow(x, -3), -3 * std::pow(x, -4)},
        {"select(x - 0.37, 1 / x, x * x)", x, x * x, 2 * x},
        {"select(c0, 1 / x, x * x)", x, 1 / x, -1 / (x * x)},
        {"c0 * x^2 + c1 / x + k", x, 1.5 * x * x - 0.25 / x + 2.5, 3 * x + 0.25 / (x * x)},
        {"y * x", x, 0.5 * x, 0.5},  // y is another input: a constant for d/dx
        {"exp(-x^2) * cos(3 * x)", x, std::exp(-x * x) * std::cos(3 * x),
         -2 * x * std::exp(-x * x) * std::cos(3 * x) - 3 * std::exp(-x * x) * std::sin(3 * x)},
        {"x / (1 + x)", x, x / (1 + x), 1 / ((1 + x) * (1 + x))},
        {"-x + 2 - x * 3", x, -4 * x + 2, -4.0},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(std::string(c.text) + " at x = " + std::to_string(c.x));
        const ValueAndSlope got = evaluate(c.text, c.x);
        EXPECT_NEAR(got.value, c.value, 1e-14 * (1 + std::abs(c.value)));
        EXPECT_NEAR(got.slope, c.slope, 1e-13 * (1 + std::abs(c.slope)));
    }
}

// Derivatives of a composition against central differences, in double and in float.
TEST(ExpressionDerivatives, CompositionAgainstCentralDifferences) {
    const char* text = "4 * k * ((1.1 / x)^12 - (1.1 / x)^6) + tanh(x - c0) * log(1 + x^2) - atan(sqrt(x))";
    for (double x : {0.9, 1.3, 2.2}) {
        const double h = 1e-6;
        const double numerical = (evaluate(text, x + h).value - evaluate(text, x - h).value) / (2 * h);
        const double analytic = evaluate(text, x).slope;
        EXPECT_NEAR(analytic, numerical, 1e-7 * std::abs(analytic)) << "x = " << x;
    }
}

TEST(ExpressionDerivatives, TheInterpreterRunsInFloat) {
    Expression e;
    const int root = parse("c0 * exp(-x) + x^3", test_names, e);
    const Program p = compile(e, {root, differentiate(e, root, 0)});
    std::vector<float> constants(p.constants.begin(), p.constants.end());
    const ProgramView<float> view{p.code.data(), constants.data(), static_cast<int>(p.code.size())};
    const float inputs[2] = {0.8f, 0.0f}, columns[1] = {1.5f};
    float out[2];
    run_program(view, inputs, columns, out);
    EXPECT_NEAR(out[0], 1.5 * std::exp(-0.8) + 0.512, 1e-6);
    EXPECT_NEAR(out[1], -1.5 * std::exp(-0.8) + 3 * 0.64, 1e-6);
}

}  // namespace
}  // namespace structmd::expression::test
