// The source emitter (for a runtime-compiled CUDA path): its statements are well formed, declare
// each temporary before use, assign every output, and compute what the bytecode computes.
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>

#include "expression/source_emitter.hpp"
#include "expression_test_support.hpp"

namespace structmd::expression::test {
namespace {

TEST(ExpressionEmitter, EmitsOneStatementPerNodeAndEveryOutput) {
    Expression e;
    const int root = parse("c0 * (sin(k * x) + step(x - 1) * x^3) / select(c1, x, 2) + min(x, c0)", test_names, e);
    const int slope = differentiate(e, root, 0);
    const std::string source =
        emit_source(e, {root, slope}, {"energy", "dudx"}, {"float", {"r", "unused"}, {"p.columns[0]", "p.columns[1]"}});
    SCOPED_TRACE(source);
    EXPECT_EQ(source.front(), '{');
    EXPECT_EQ(source.substr(source.size() - 2), "}\n");
    int depth = 0;
    for (char c : source) {
        depth += c == '(' ? 1 : c == ')' ? -1 : 0;
        ASSERT_GE(depth, 0);
    }
    EXPECT_EQ(depth, 0);
    // Every temporary is declared once, before any statement reads it.
    std::istringstream lines(source);
    std::string line;
    std::set<std::string> declared;
    const std::regex declaration(R"(^const float (t\d+) = (.*);$)");
    const std::regex temporary(R"(\bt\d+\b)");
    int assignments = 0;
    while (std::getline(lines, line)) {
        if (line == "{" || line == "}") continue;
        std::smatch m;
        std::string used = line;
        if (std::regex_match(line, m, declaration)) {
            EXPECT_TRUE(declared.insert(m[1]).second) << m[1] << " declared twice";
            used = m[2];
        } else {
            ++assignments;
            EXPECT_TRUE(line.rfind("energy = t", 0) == 0 || line.rfind("dudx = t", 0) == 0) << line;
            used = line.substr(line.find('=') + 1);
        }
        for (auto it = std::sregex_iterator(used.begin(), used.end(), temporary); it != std::sregex_iterator(); ++it)
            EXPECT_TRUE(declared.count(it->str())) << it->str() << " read before it is declared: " << line;
    }
    EXPECT_EQ(assignments, 2);
    EXPECT_NE(source.find("= r;"), std::string::npos);
    EXPECT_NE(source.find("p.columns[0]"), std::string::npos);
    EXPECT_NE(source.find("sin("), std::string::npos);
    EXPECT_NE(source.find("cos("), std::string::npos);  // the derivative
    EXPECT_EQ(source.find("unused"), std::string::npos);
}

TEST(ExpressionEmitter, ConstantsKeepEveryDigit) {
    Expression e;
    const int root = parse("0.1 * x", test_names, e);
    const std::string source = emit_source(e, {root}, {"energy"}, {"double", {"r"}, {}});
    EXPECT_NE(source.find("double(0.10000000000000001)"), std::string::npos) << source;
}

}  // namespace
}  // namespace structmd::expression::test
