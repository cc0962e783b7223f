#include "expression/expression.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

namespace structmd::expression {

namespace {

uint64_t bits_of(double x) {
    if (x == 0.0) x = 0.0;  // -0 and +0 are one constant
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return bits;
}

void post_order(const Expression& e, int root, std::vector<char>& seen, std::vector<int>& order) {
    // Each entry: a node and how many of its operands (a, b, c) have been looked at.
    std::vector<std::pair<int, int>> stack;
    if (!seen[root]) stack.push_back({root, 0});
    seen[root] = 1;
    while (!stack.empty()) {
        auto& [id, next] = stack.back();
        const Node& n = e.node(id);
        const int operands[3] = {n.a, n.b, n.c};
        if (next == 3) {
            order.push_back(id);
            stack.pop_back();
            continue;
        }
        const int operand = operands[next++];
        if (operand >= 0 && !seen[operand]) {
            seen[operand] = 1;
            stack.push_back({operand, 0});
        }
    }
}

bool commutative(Op op) { return op == Op::add || op == Op::mul || op == Op::min || op == Op::max; }

}  // namespace

std::vector<int> nodes_in_order(const Expression& e, const std::vector<int>& roots) {
    std::vector<char> seen(e.size(), 0);
    std::vector<int> order;
    for (int root : roots) post_order(e, root, seen, order);
    return order;
}

int Expression::make(const Node& given) {
    Node n = given;
    for (int operand : {n.a, n.b, n.c})
        if (operand >= 0) n.depth = std::max(n.depth, nodes_[operand].depth + 1);
    if (n.depth > kMaxExpressionDepth)
        throw ExpressionError(0, "nested more than " + std::to_string(kMaxExpressionDepth) +
                                     " operations deep with its derivative: split it into several terms");
    const auto key = std::make_tuple(static_cast<int>(n.op), n.a, n.b, n.c, n.index,
                                     n.op == Op::constant ? bits_of(n.value) : 0);
    const auto found = known_.find(key);
    if (found != known_.end()) return found->second;
    nodes_.push_back(n);
    const int id = static_cast<int>(nodes_.size()) - 1;
    known_.emplace(key, id);
    return id;
}

// The node of an operation whose operands are all constants, as a constant; -1 otherwise.
int Expression::fold(Op op, int a, int b, int c) {
    const auto value = [&](int id) { return id < 0 ? 0.0 : nodes_[id].value; };
    for (int id : {a, b, c})
        if (id >= 0 && nodes_[id].op != Op::constant) return -1;
    return constant(apply<double>(op, value(a), value(b), value(c), 0));
}

int Expression::constant(double value) {
    Node n;
    n.op = Op::constant;
    n.value = value;
    return make(n);
}

int Expression::input(int slot) {
    Node n;
    n.op = Op::input;
    n.index = slot;
    return make(n);
}

int Expression::column(int slot) {
    Node n;
    n.op = Op::column;
    n.index = slot;
    return make(n);
}

int Expression::unary(Op op, int a) {
    if (const int folded = fold(op, a); folded >= 0) return folded;
    const Node& x = nodes_[a];
    if (op == Op::neg && x.op == Op::neg) return x.a;
    if (op == Op::step && x.op == Op::step) return constant(1.0);  // step of 0 or 1
    Node n;
    n.op = op;
    n.a = a;
    return make(n);
}

int Expression::binary(Op op, int a, int b) {
    if (const int folded = fold(op, a, b); folded >= 0) return folded;
    if (commutative(op) && (is_constant(b) || (!is_constant(a) && b < a))) std::swap(a, b);  // constants first
    switch (op) {
        case Op::add:
            if (is_constant(a, 0.0)) return b;
            if (nodes_[b].op == Op::neg) return binary(Op::sub, a, nodes_[b].a);
            if (a == b) return binary(Op::mul, constant(2.0), a);
            break;
        case Op::sub:
            if (is_constant(b, 0.0)) return a;
            if (is_constant(a, 0.0)) return unary(Op::neg, b);
            if (a == b) return constant(0.0);
            if (nodes_[b].op == Op::neg) return binary(Op::add, a, nodes_[b].a);
            break;
        case Op::mul:
            if (is_constant(a, 0.0)) return a;
            if (is_constant(a, 1.0)) return b;
            if (is_constant(a, -1.0)) return unary(Op::neg, b);
            if (nodes_[b].op == Op::neg) return unary(Op::neg, binary(Op::mul, a, nodes_[b].a));
            if (is_constant(a) && nodes_[b].op == Op::mul && is_constant(nodes_[b].a))
                return binary(Op::mul, constant(nodes_[a].value * nodes_[nodes_[b].a].value), nodes_[b].b);
            if (a == b) return powi(a, 2);
            break;
        case Op::div:
            if (is_constant(a, 0.0)) return a;
            if (is_constant(b, 1.0)) return a;
            if (a == b) return constant(1.0);
            break;
        case Op::pow: {
            const Node& e = nodes_[b];
            if (e.op == Op::constant && e.value == std::floor(e.value) && std::fabs(e.value) <= 64.0)
                return powi(a, static_cast<int>(e.value));
            if (is_constant(b, 0.5)) return unary(Op::sqrt, a);
            break;
        }
        case Op::min:
        case Op::max:
            if (a == b) return a;
            break;
        default: break;
    }
    Node n;
    n.op = op;
    n.a = a;
    n.b = b;
    return make(n);
}

int Expression::powi(int a, int exponent) {
    if (exponent == 0) return constant(1.0);
    if (exponent == 1) return a;
    if (is_constant(a)) return constant(integer_power(nodes_[a].value, exponent));
    if (nodes_[a].op == Op::powi) {
        const long long product = static_cast<long long>(nodes_[a].index) * exponent;
        if (product >= -64 && product <= 64) return powi(nodes_[a].a, static_cast<int>(product));
    }
    Node n;
    n.op = Op::powi;
    n.a = a;
    n.index = exponent;
    return make(n);
}

int Expression::select(int condition, int a, int b) {
    if (is_constant(condition)) return nodes_[condition].value != 0.0 ? a : b;
    if (a == b) return a;
    Node n;
    n.op = Op::select;
    n.a = condition;
    n.b = a;
    n.c = b;
    return make(n);
}

}  // namespace structmd::expression
