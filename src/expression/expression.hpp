#pragma once
// An expression as a graph of shared nodes (a DAG): every node is made through Expression, which
// folds constants, applies the identities of 0 and 1 and returns the existing node for a repeated
// (operation, operands) key. Equal subexpressions are therefore one node, which the compiler
// (compiler.hpp) evaluates once: the energy and its derivative share their common terms for free.
// Leaves are numbers, the independent variables of the component (r, theta, phi, x, y, z: `input`
// slots) and the data columns (`column` slots); the keys of "parameters" are numbers by the time
// the expression is built.
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "core/error.hpp"
#include "expression/operations.hpp"

namespace structmd::expression {

struct Node {
    Op op = Op::constant;
    int a = -1, b = -1, c = -1;  // operands (node ids)
    double value = 0.0;          // constant
    int index = 0;               // input or column slot; powi exponent
    int depth = 1;               // 1 + the deepest operand's
};

// The deepest a node may sit: the walks over an expression (its derivative, the compilers) recurse
// this deep at most, on any thread's stack. The parser keeps what it reads to a quarter of it, so
// that derivatives fit too.
inline constexpr int kMaxExpressionDepth = 2000;
inline constexpr int kMaxParsedDepth = kMaxExpressionDepth / 4;
// How deep parentheses, signs, powers and calls may nest in the text: the parser recurses through
// a few frames per level.
inline constexpr int kMaxParsedNesting = 100;

// An error in an expression, at a 1-based character position of its text (0: no one position).
class ExpressionError : public Error {
public:
    ExpressionError(int column, const std::string& what)
        : Error(STRUCTMD_ERR_INPUT, column > 0 ? "at column " + std::to_string(column) + ": " + what : what),
          column_(column) {}
    int column() const { return column_; }

private:
    int column_;
};

class Expression {
public:
    int constant(double value);
    int input(int slot);
    int column(int slot);
    int unary(Op op, int a);
    int binary(Op op, int a, int b);
    int powi(int a, int exponent);
    int select(int condition, int a, int b);

    const Node& node(int id) const { return nodes_.at(id); }
    size_t size() const { return nodes_.size(); }
    bool is_constant(int id, double value) const { return nodes_[id].op == Op::constant && nodes_[id].value == value; }
    bool is_constant(int id) const { return nodes_[id].op == Op::constant; }

private:
    int make(const Node& n);
    int fold(Op op, int a, int b = -1, int c = -1);

    std::vector<Node> nodes_;
    std::map<std::tuple<int, int, int, int, int, uint64_t>, int> known_;
};

// Every node the roots depend on, each once and after its operands (depth-first, roots in order;
// iterative, so any depth).
std::vector<int> nodes_in_order(const Expression& e, const std::vector<int>& roots);

}  // namespace structmd::expression
