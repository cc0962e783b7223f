// Parsing: precedence and associativity, numbers, and the column of every kind of error.
#include <gtest/gtest.h>

#include <cmath>

#include "expression_test_support.hpp"

namespace structmd::expression::test {
namespace {

double value(const std::string& text, double x = 3.0) { return evaluate(text, x).value; }

TEST(ExpressionParse, Precedence) {
    EXPECT_DOUBLE_EQ(value("1 + 2 * 3"), 7.0);
    EXPECT_DOUBLE_EQ(value("(1 + 2) * 3"), 9.0);
    EXPECT_DOUBLE_EQ(value("8 / 4 / 2"), 1.0);   // left-associative
    EXPECT_DOUBLE_EQ(value("8 - 4 - 2"), 2.0);
    EXPECT_DOUBLE_EQ(value("2 ^ 3 ^ 2"), 512.0);  // right-associative: 2^(3^2)
    EXPECT_DOUBLE_EQ(value("-x^2"), -9.0);        // -(x^2)
    EXPECT_DOUBLE_EQ(value("(-x)^2"), 9.0);
    EXPECT_DOUBLE_EQ(value("2^-1"), 0.5);
    EXPECT_DOUBLE_EQ(value("- -x"), 3.0);
    EXPECT_DOUBLE_EQ(value("+x"), 3.0);
    EXPECT_DOUBLE_EQ(value("2 * x ^ 2"), 18.0);
    EXPECT_DOUBLE_EQ(value("-2 ^ 2"), -4.0);
    EXPECT_DOUBLE_EQ(value("x^0.5"), std::sqrt(3.0));
    EXPECT_DOUBLE_EQ(value("x^-2.5"), std::pow(3.0, -2.5));
}

TEST(ExpressionParse, NumbersAndNames) {
    EXPECT_DOUBLE_EQ(value("1e-3"), 1e-3);
    EXPECT_DOUBLE_EQ(value("2.5E+2"), 250.0);
    EXPECT_DOUBLE_EQ(value(".5"), 0.5);
    EXPECT_DOUBLE_EQ(value("k * x"), 7.5);
    EXPECT_DOUBLE_EQ(value("c0 + c1 * y"), 1.5 - 0.125);
    EXPECT_DOUBLE_EQ(value("  x  *\tx "), 9.0);
}

TEST(ExpressionParse, SelectAndStep) {
    EXPECT_DOUBLE_EQ(value("select(x - 3, 1, 2)"), 2.0);
    EXPECT_DOUBLE_EQ(value("select(x, 1, 2)"), 1.0);
    EXPECT_DOUBLE_EQ(value("step(x - 3)"), 1.0);  // step(0) = 1
    EXPECT_DOUBLE_EQ(value("step(x - 3.5)"), 0.0);
}

TEST(ExpressionParse, ComparisonsAreOneOrZeroAndBindLoosest) {
    EXPECT_DOUBLE_EQ(value("x < 3.5"), 1.0);
    EXPECT_DOUBLE_EQ(value("x < 3"), 0.0);  // strict at equality
    EXPECT_DOUBLE_EQ(value("x <= 3"), 1.0);
    EXPECT_DOUBLE_EQ(value("x <= 2.5"), 0.0);
    EXPECT_DOUBLE_EQ(value("x > 3"), 0.0);
    EXPECT_DOUBLE_EQ(value("x > 2"), 1.0);
    EXPECT_DOUBLE_EQ(value("x >= 3"), 1.0);
    EXPECT_DOUBLE_EQ(value("x >= 3.5"), 0.0);
    EXPECT_DOUBLE_EQ(value("x + 1 < 2 * x"), 1.0);  // (x + 1) < (2 x): sums on both sides
    EXPECT_DOUBLE_EQ(value("2 * (x < 4) + (x > 4)"), 2.0);
    EXPECT_DOUBLE_EQ(value("select(x >= 3, 5, 6)"), 5.0);
    EXPECT_DOUBLE_EQ(evaluate("(x < 4) * x^2", 3.0).slope, 6.0);  // the comparison's derivative is 0
    std::string message;
    EXPECT_EQ(error_column("1 < x < 4", &message), 7);
    EXPECT_NE(message.find("do not chain"), std::string::npos) << message;
    EXPECT_EQ(error_column("x <"), 4);
}

TEST(ExpressionParse, ErrorsNameTheirColumn) {
    std::string message;
    EXPECT_EQ(error_column("x + * 2", &message), 5);
    EXPECT_NE(message.find("column 5"), std::string::npos) << message;
    EXPECT_EQ(error_column("x + foo", &message), 5);
    EXPECT_NE(message.find("unknown variable 'foo'"), std::string::npos) << message;
    EXPECT_EQ(error_column("2 * bar(x)", &message), 5);
    EXPECT_NE(message.find("unknown function 'bar'"), std::string::npos) << message;
    EXPECT_EQ(error_column("1 + min(x)", &message), 5);
    EXPECT_NE(message.find("min() takes 2 arguments, got 1"), std::string::npos) << message;
    EXPECT_EQ(error_column("sqrt(x, 2)", &message), 1);
    EXPECT_EQ(error_column("select(x, 1)"), 1);
    EXPECT_EQ(error_column("(x + 1"), 7);
    EXPECT_EQ(error_column("x + 1)"), 6);
    EXPECT_EQ(error_column("x $ 1"), 3);
    EXPECT_EQ(error_column(""), 1);
    EXPECT_EQ(error_column("x +"), 4);
    EXPECT_EQ(error_column("2x"), 2);
    EXPECT_EQ(error_column("x y"), 3);
    EXPECT_EQ(error_column("sin x"), 5);
    EXPECT_EQ(error_column("x + 1"), 0);
}

TEST(ExpressionParse, ConstantsFoldAndEqualTermsAreShared) {
    Expression e;
    const int root = parse("(2 * 3 + 1) * x + sin(x) * sin(x) + 0 * y", test_names, e);
    const Program p = compile(e, {root});
    // 7 * x + sin(x)^2: load 7, load x, mul, sin, powi, add, output.
    EXPECT_EQ(p.code.size(), 7u);
    EXPECT_EQ(p.constants, std::vector<double>{7.0});
    EXPECT_DOUBLE_EQ(p.run({3.0, 0.0}, {})[0], 21.0 + std::sin(3.0) * std::sin(3.0));
}

TEST(ExpressionParse, RegistersAreReused) {
    // A long sum of distinct terms needs only a few live values at a time.
    std::string text = "0";
    for (int k = 1; k <= 200; ++k) text += " + sin(" + std::to_string(k) + " * x)";
    Expression e;
    const int root = parse(text, test_names, e);
    const Program p = compile(e, {root, differentiate(e, root, 0)});
    EXPECT_LE(p.registers, 8);
    double expected = 0.0, slope = 0.0;
    for (int k = 1; k <= 200; ++k) {
        expected += std::sin(k * 0.3);
        slope += k * std::cos(k * 0.3);
    }
    const std::vector<double> out = p.run({0.3, 0.0}, {});
    EXPECT_NEAR(out[0], expected, 1e-12 * std::abs(expected) + 1e-12);
    EXPECT_NEAR(out[1], slope, 1e-12 * std::abs(slope));
}

}  // namespace
}  // namespace structmd::expression::test
