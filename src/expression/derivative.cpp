#include "expression/derivative.hpp"

#include <unordered_map>

namespace structmd::expression {

namespace {

class Differentiator {
public:
    Differentiator(Expression& e, int slot) : e_(e), slot_(slot) {}

    int d(int id) {
        const auto found = done_.find(id);
        if (found != done_.end()) return found->second;
        const int result = rule(id);
        done_.emplace(id, result);
        return result;
    }

private:
    int k(double value) { return e_.constant(value); }
    int add(int a, int b) { return e_.binary(Op::add, a, b); }
    int sub(int a, int b) { return e_.binary(Op::sub, a, b); }
    int mul(int a, int b) { return e_.binary(Op::mul, a, b); }
    int div(int a, int b) { return e_.binary(Op::div, a, b); }
    int neg(int a) { return e_.unary(Op::neg, a); }
    int f(Op op, int a) { return e_.unary(op, a); }

    int rule(int id) {
        const Node n = e_.node(id);  // a copy: making nodes may move the graph's storage
        switch (n.op) {
            case Op::constant:
            case Op::column: return k(0.0);
            case Op::input: return k(n.index == slot_ ? 1.0 : 0.0);
            default: break;
        }
        const int a = n.a, b = n.b;
        if (n.op == Op::select) {
            const int dy = d(n.b), dz = d(n.c);
            return e_.select(a, dy, dz);
        }
        const int da = d(a);
        if (e_.is_constant(da, 0.0) && (arity(n.op) == 1 || e_.is_constant(d(b), 0.0))) return k(0.0);
        switch (n.op) {
            case Op::add: return add(da, d(b));
            case Op::sub: return sub(da, d(b));
            case Op::mul: return add(mul(da, b), mul(a, d(b)));
            case Op::div: return div(sub(da, mul(id, d(b))), b);  // (a' - (a/b) b') / b
            case Op::neg: return neg(da);
            case Op::pow: {
                const int db = d(b);
                if (e_.is_constant(db, 0.0)) return mul(mul(b, e_.binary(Op::pow, a, sub(b, k(1.0)))), da);
                return mul(id, add(mul(db, f(Op::log, a)), div(mul(b, da), a)));
            }
            case Op::powi: return mul(mul(k(n.index), e_.powi(a, n.index - 1)), da);
            case Op::sqrt: return div(da, mul(k(2.0), id));
            case Op::exp: return mul(id, da);
            case Op::log: return div(da, a);
            case Op::sin: return mul(f(Op::cos, a), da);
            case Op::cos: return neg(mul(f(Op::sin, a), da));
            case Op::tan: return mul(add(k(1.0), e_.powi(id, 2)), da);
            case Op::acos: return neg(div(da, f(Op::sqrt, sub(k(1.0), e_.powi(a, 2)))));
            case Op::asin: return div(da, f(Op::sqrt, sub(k(1.0), e_.powi(a, 2))));
            case Op::atan: return div(da, add(k(1.0), e_.powi(a, 2)));
            case Op::tanh: return mul(sub(k(1.0), e_.powi(id, 2)), da);
            case Op::cosh: return mul(f(Op::sinh, a), da);
            case Op::sinh: return mul(f(Op::cosh, a), da);
            case Op::abs: return mul(e_.select(f(Op::step, a), k(1.0), k(-1.0)), da);
            case Op::min: return e_.select(f(Op::step, sub(b, a)), da, d(b));
            case Op::max: return e_.select(f(Op::step, sub(a, b)), da, d(b));
            case Op::step: return k(0.0);
            default: break;
        }
        throw Error(STRUCTMD_ERR_INTERNAL, "expression: no derivative rule for an operation");
    }

    Expression& e_;
    int slot_;
    std::unordered_map<int, int> done_;
};

}  // namespace

int differentiate(Expression& e, int root, int inputSlot) { return Differentiator(e, inputSlot).d(root); }

}  // namespace structmd::expression
