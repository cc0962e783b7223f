#include "expression/parser.hpp"

#include <cctype>
#include <cstdlib>
#include <vector>

namespace structmd::expression {

namespace {

struct Function {
    const char* name;
    Op op;
    int arguments;
};

const std::vector<Function>& functions() {
    static const std::vector<Function> all = {
        {"sqrt", Op::sqrt, 1}, {"exp", Op::exp, 1},   {"log", Op::log, 1},   {"sin", Op::sin, 1},
        {"cos", Op::cos, 1},   {"tan", Op::tan, 1},   {"acos", Op::acos, 1}, {"asin", Op::asin, 1},
        {"atan", Op::atan, 1}, {"tanh", Op::tanh, 1}, {"cosh", Op::cosh, 1}, {"sinh", Op::sinh, 1},
        {"abs", Op::abs, 1},   {"step", Op::step, 1}, {"min", Op::min, 2},   {"max", Op::max, 2},
        {"pow", Op::pow, 2},   {"select", Op::select, 3}};
    return all;
}

class Parser {
public:
    Parser(const std::string& text, const Resolver& resolve, Expression& e) : text_(text), resolve_(resolve), e_(e) {}

    int parse() {
        skip_space();
        if (at_end()) throw ExpressionError(1, "the expression is empty");
        const int root = comparison();
        skip_space();
        if (!at_end()) throw ExpressionError(column(), std::string("unexpected '") + text_[pos_] + "'");
        return root;
    }

private:
    bool at_end() const { return pos_ >= text_.size(); }
    int column() const { return static_cast<int>(pos_) + 1; }
    void skip_space() {
        while (!at_end() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    }
    // Consumes c (after spaces) if it is next.
    bool accept(char c) {
        skip_space();
        if (!at_end() && text_[pos_] == c) {
            ++pos_;
            return true;
        }
        return false;
    }
    void expect(char c, const std::string& what) {
        if (!accept(c))
            throw ExpressionError(column(), "expected " + what +
                                                (at_end() ? " at the end" : std::string(", got '") + text_[pos_] + "'"));
    }

    // Every recursion of the parser ('(', a sign, '^', a function's arguments) passes through
    // unary(): the text decides how deep, so the depth is bounded there (30,000 nested parentheses
    // overflowed the stack).
    class Nested {
    public:
        explicit Nested(Parser& p) : p_(p) {
            if (++p_.nesting_ > kMaxParsedNesting)
                throw ExpressionError(p_.column(), "nested more than " + std::to_string(kMaxParsedNesting) + " deep");
        }
        ~Nested() { --p_.nesting_; }
        Nested(const Nested&) = delete;
        Nested& operator=(const Nested&) = delete;

    private:
        Parser& p_;
    };

    // A node as deep as the walks over the expression allow (a sum of 100,000 terms is a chain that
    // deep), or an error at the column reached.
    int within_depth(int id) {
        if (e_.node(id).depth > kMaxParsedDepth)
            throw ExpressionError(column(), "more than " + std::to_string(kMaxParsedDepth) +
                                                " operations deep (each term of a long sum or product counts): split "
                                                "it into several terms");
        return id;
    }

    // A left-associative chain of `next` joined by the operators `first` and `second`.
    int chain(int (Parser::*next)(), char first, Op firstOp, char second, Op secondOp) {
        int left = (this->*next)();
        for (;;) {
            if (accept(first))
                left = within_depth(e_.binary(firstOp, left, (this->*next)()));
            else if (accept(second))
                left = within_depth(e_.binary(secondOp, left, (this->*next)()));
            else
                return left;
        }
    }
    // The loosest binding: at most one comparison of two sums, 1 where it holds and 0 elsewhere,
    // written with step (1 for x >= 0): a >= b is step(a - b), a < b is 1 - step(a - b), a <= b is
    // step(b - a), a > b is 1 - step(b - a). Its derivative is 0, as step's.
    int comparison() {
        const int left = sum();
        skip_space();
        if (at_end() || (text_[pos_] != '<' && text_[pos_] != '>')) return left;
        const bool less = text_[pos_++] == '<';
        const bool orEqual = !at_end() && text_[pos_] == '=';
        if (orEqual) ++pos_;
        const int right = sum();
        skip_space();
        if (!at_end() && (text_[pos_] == '<' || text_[pos_] == '>'))
            throw ExpressionError(column(), "comparisons do not chain: write (a < b) * (b < c)");
        const int difference = within_depth(less == orEqual ? e_.binary(Op::sub, right, left)
                                                            : e_.binary(Op::sub, left, right));
        const int stepped = within_depth(e_.unary(Op::step, difference));
        return orEqual ? stepped : within_depth(e_.binary(Op::sub, e_.constant(1.0), stepped));
    }
    int sum() { return chain(&Parser::product, '+', Op::add, '-', Op::sub); }
    int product() { return chain(&Parser::unary, '*', Op::mul, '/', Op::div); }

    int unary() {
        const Nested nested(*this);
        if (accept('-')) return within_depth(e_.unary(Op::neg, unary()));
        if (accept('+')) return unary();
        return power();
    }

    int power() {
        const int base = primary();
        if (accept('^')) return within_depth(e_.binary(Op::pow, base, unary()));
        return base;
    }

    int primary() {
        skip_space();
        if (at_end()) throw ExpressionError(column(), "expected a number, a name or '(' at the end");
        const char c = text_[pos_];
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
        if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return named();
        if (accept('(')) {
            const int inner = comparison();
            expect(')', "')'");
            return inner;
        }
        throw ExpressionError(column(), std::string("unexpected '") + c + "'");
    }

    int number() {
        const int start = column();
        const char* begin = text_.c_str() + pos_;
        char* end = nullptr;
        const double value = std::strtod(begin, &end);
        if (end == begin) throw ExpressionError(start, "malformed number");
        pos_ += static_cast<size_t>(end - begin);
        if (!at_end() && (std::isalpha(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_'))
            throw ExpressionError(column(), "malformed number");
        return e_.constant(value);
    }

    int named() {
        const int start = column();
        const size_t first = pos_;
        while (!at_end() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
        const std::string name = text_.substr(first, pos_ - first);
        skip_space();
        if (!at_end() && text_[pos_] == '(') return call(name, start);
        for (const Function& f : functions())
            if (name == f.name) throw ExpressionError(column(), "expected '(' after the function '" + name + "'");
        const Binding b = resolve_(name);
        switch (b.kind) {
            case Binding::Kind::input: return e_.input(b.slot);
            case Binding::Kind::column: return e_.column(b.slot);
            case Binding::Kind::number: return e_.constant(b.value);
            case Binding::Kind::unknown: break;
        }
        throw ExpressionError(start, "unknown variable '" + name + "'");
    }

    int call(const std::string& name, int start) {
        const Function* f = nullptr;
        for (const Function& known : functions())
            if (name == known.name) f = &known;
        if (!f) throw ExpressionError(start, "unknown function '" + name + "' (functions: " + function_names() + ")");
        expect('(', "'('");
        std::vector<int> args;
        if (!accept(')')) {
            do args.push_back(comparison());
            while (accept(','));
            expect(')', "',' or ')'");
        }
        if (static_cast<int>(args.size()) != f->arguments)
            throw ExpressionError(start, name + "() takes " + std::to_string(f->arguments) + " argument" +
                                             (f->arguments == 1 ? "" : "s") + ", got " + std::to_string(args.size()));
        if (f->arguments == 1) return within_depth(e_.unary(f->op, args[0]));
        if (f->arguments == 2) return within_depth(e_.binary(f->op, args[0], args[1]));
        return within_depth(e_.select(args[0], args[1], args[2]));
    }

    const std::string& text_;
    const Resolver& resolve_;
    Expression& e_;
    size_t pos_ = 0;
    int nesting_ = 0;
};

}  // namespace

int parse(const std::string& text, const Resolver& resolve, Expression& into) {
    return Parser(text, resolve, into).parse();
}

std::string function_names() {
    std::string names;
    for (const Function& f : functions()) names += (names.empty() ? "" : ", ") + std::string(f.name);
    return names;
}

}  // namespace structmd::expression
