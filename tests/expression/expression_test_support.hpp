#pragma once
// Compiling and running an expression of the variables x (input 0), y (input 1) and the columns
// c0, c1 for the language tests; every other name is unknown, except k = 2.5 (a parameter).
#include <string>
#include <vector>

#include "expression/compiler.hpp"
#include "expression/derivative.hpp"
#include "expression/parser.hpp"

namespace structmd::expression::test {

inline Binding test_names(const std::string& name) {
    if (name == "x") return {Binding::Kind::input, 0, 0.0};
    if (name == "y") return {Binding::Kind::input, 1, 0.0};
    if (name == "c0") return {Binding::Kind::column, 0, 0.0};
    if (name == "c1") return {Binding::Kind::column, 1, 0.0};
    if (name == "k") return {Binding::Kind::number, 0, 2.5};
    return {};
}

// The value and d/dx of `text` at x (y = 0.5, c0 = 1.5, c1 = -0.25), through the bytecode.
struct ValueAndSlope {
    double value, slope;
};

inline ValueAndSlope evaluate(const std::string& text, double x) {
    Expression e;
    const int root = parse(text, test_names, e);
    const int slope = differentiate(e, root, 0);
    const Program p = compile(e, {root, slope});
    const std::vector<double> out = p.run({x, 0.5}, {1.5, -0.25});
    return {out[0], out[1]};
}

// The 1-based column an expression's error names (0: it parsed).
inline int error_column(const std::string& text, std::string* message = nullptr) {
    Expression e;
    try {
        parse(text, test_names, e);
    } catch (const ExpressionError& error) {
        if (message) *message = error.what();
        return error.column();
    }
    return 0;
}

}  // namespace structmd::expression::test
