#pragma once
// The text of an expression to its node (expression.hpp). Grammar, loosest binding first:
//   compare := sum (('<' | '<=' | '>' | '>=') sum)?   1 where it holds, 0 elsewhere; not chained
//   sum     := product (('+' | '-') product)*
//   product := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power          so -x^2 is -(x^2)
//   power   := primary ('^' unary)?               right-associative: a^b^c is a^(b^c); 2^-1 is 1/2
//   primary := number | name | name '(' compare (',' compare)* ')' | '(' compare ')'
// Numbers: 12, 1.5, .5, 1e-3, 2.5E+4. Functions: sqrt exp log sin cos tan acos asin atan tanh cosh
// sinh abs step (one argument), min max pow (two), select (three: select(c, a, b) is a where c != 0,
// else b). Every other name is a variable, which the caller's resolver turns into an input, a data
// column or a number. Errors are ExpressionError at the 1-based column of the culprit.
#include <functional>
#include <string>

#include "expression/expression.hpp"

namespace structmd::expression {

// What a name stands for.
struct Binding {
    enum class Kind { unknown, input, column, number } kind = Kind::unknown;
    int slot = 0;       // input or column slot
    double value = 0;   // number
};

using Resolver = std::function<Binding(const std::string& name)>;

// Parses `text` into `into` and returns the root node.
int parse(const std::string& text, const Resolver& resolve, Expression& into);

// The names of the functions of the grammar, for messages ("sqrt, exp, ...").
std::string function_names();

}  // namespace structmd::expression
