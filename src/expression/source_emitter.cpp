#include "expression/source_emitter.hpp"

#include <cstdio>
#include <sstream>

#include "core/precise.hpp"

namespace structmd::expression {

namespace {

std::string literal(double value, const std::string& real) {
    const std::string s = precise(value);
    if (s == "inf" || s == "-inf" || s == "nan" || s == "-nan")
        return "(" + real + ")(" + (s == "inf" ? "1.0/0.0" : s == "-inf" ? "-1.0/0.0" : "0.0/0.0") + ")";
    return real + "(" + s + ")";
}

const char* function_of(Op op) {
    switch (op) {
        case Op::sqrt: return "sqrt";
        case Op::exp: return "exp";
        case Op::log: return "log";
        case Op::sin: return "sin";
        case Op::cos: return "cos";
        case Op::tan: return "tan";
        case Op::acos: return "acos";
        case Op::asin: return "asin";
        case Op::atan: return "atan";
        case Op::tanh: return "tanh";
        case Op::cosh: return "cosh";
        case Op::sinh: return "sinh";
        case Op::abs: return "fabs";
        case Op::pow: return "pow";
        default: return nullptr;
    }
}

// x^n as products of x (repeated squaring, as the interpreter does).
std::string integer_power(const std::string& x, int n, const std::string& real) {
    if (n < 0) return "(" + real + "(1) / " + integer_power(x, -n, real) + ")";
    if (n == 1) return x;
    if (n % 2 == 0) {
        const std::string half = integer_power(x, n / 2, real);
        return "(" + half + " * " + half + ")";
    }
    return "(" + x + " * " + integer_power(x, n - 1, real) + ")";
}

}  // namespace

std::string emit_source(const Expression& e, const std::vector<int>& roots, const std::vector<std::string>& outputs,
                        const SourceNames& names) {
    if (outputs.size() != roots.size())
        throw Error(STRUCTMD_ERR_INTERNAL, "emit_source: one output name per root is needed");
    const std::vector<int> order = nodes_in_order(e, roots);
    std::vector<std::string> nameOf(e.size());
    const std::string& real = names.real;
    std::ostringstream out;
    out << "{\n";
    for (int id : order) {
        const Node& n = e.node(id);
        const std::string a = n.a >= 0 ? nameOf[n.a] : "", b = n.b >= 0 ? nameOf[n.b] : "",
                          c = n.c >= 0 ? nameOf[n.c] : "";
        std::string value;
        switch (n.op) {
            case Op::constant: value = literal(n.value, real); break;
            case Op::input: value = names.inputs.at(n.index); break;
            case Op::column: value = names.columns.at(n.index); break;
            case Op::add: value = a + " + " + b; break;
            case Op::sub: value = a + " - " + b; break;
            case Op::mul: value = a + " * " + b; break;
            case Op::div: value = a + " / " + b; break;
            case Op::neg: value = "-" + a; break;
            case Op::powi: value = integer_power(a, n.index, real); break;
            case Op::min: value = a + " < " + b + " ? " + a + " : " + b; break;
            case Op::max: value = a + " > " + b + " ? " + a + " : " + b; break;
            case Op::step: value = a + " >= " + real + "(0) ? " + real + "(1) : " + real + "(0)"; break;
            case Op::select: value = a + " != " + real + "(0) ? " + b + " : " + c; break;
            default:
                value = std::string(function_of(n.op)) + "(" + a + (n.b >= 0 ? ", " + b : "") + ")";
                break;
        }
        nameOf[id] = names.prefix + std::to_string(id);
        out << "const " << real << " " << nameOf[id] << " = " << value << ";\n";
    }
    for (size_t k = 0; k < roots.size(); ++k) out << outputs[k] << " = " << nameOf[roots[k]] << ";\n";
    out << "}\n";
    return out.str();
}

}  // namespace structmd::expression
