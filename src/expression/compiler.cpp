#include "expression/compiler.hpp"

#include <algorithm>
#include <limits>
#include <map>

namespace structmd::expression {

namespace {

uint8_t small(int value) { return static_cast<uint8_t>(value); }

// The distinct operands of a node.
std::vector<int> operands_of(const Node& n) {
    std::vector<int> operands;
    for (int operand : {n.a, n.b, n.c})
        if (operand >= 0 && std::find(operands.begin(), operands.end(), operand) == operands.end())
            operands.push_back(operand);
    return operands;
}

// An evaluation order that keeps few values live. Operations are chosen greedily: among those whose
// operands are computed, the one that adds the fewest live values (its result, plus the leaves it
// loads that other readers still need, minus the operands it reads for the last time), then the
// earliest in depth-first order. Leaves are loaded just before their first reader. Depth-first order
// alone would keep every term that the value and its derivative share (k x in sin(k x) and
// k cos(k x)) live from the value's sum to the derivative's.
std::vector<int> schedule(const Expression& e, const std::vector<int>& roots) {
    const std::vector<int> depthFirst = nodes_in_order(e, roots);
    const auto leaf = [&](int id) { return arity(e.node(id).op) == 0; };
    std::vector<int> rank(e.size(), 0), readersLeft(e.size(), 0), operandsLeft(e.size(), 0);
    std::vector<char> done(e.size(), 0);
    std::vector<std::vector<int>> readers(e.size());
    for (size_t k = 0; k < depthFirst.size(); ++k) {
        const int id = depthFirst[k];
        rank[id] = static_cast<int>(k);
        for (int operand : operands_of(e.node(id))) {
            readers[operand].push_back(id);
            ++readersLeft[operand];
            if (!leaf(operand)) ++operandsLeft[id];
        }
    }
    for (int root : roots) ++readersLeft[root];  // a root is read by the program's output
    std::vector<int> ready, order;
    for (int id : depthFirst)
        if (!leaf(id) && operandsLeft[id] == 0) ready.push_back(id);
    const auto cost = [&](int id) {
        int added = 1;
        for (int operand : operands_of(e.node(id))) {
            const bool last = readersLeft[operand] == 1;
            if (done[operand] && last) --added;
            if (!done[operand] && !last) ++added;
        }
        return added;
    };
    while (!ready.empty()) {
        size_t best = 0;
        int bestCost = cost(ready[0]);
        for (size_t k = 1; k < ready.size(); ++k) {
            const int c = cost(ready[k]);
            if (c < bestCost || (c == bestCost && rank[ready[k]] < rank[ready[best]])) {
                best = k;
                bestCost = c;
            }
        }
        const int id = ready[best];
        ready.erase(ready.begin() + static_cast<long>(best));
        for (int operand : operands_of(e.node(id))) {
            if (!done[operand]) {
                order.push_back(operand);
                done[operand] = 1;
            }
            --readersLeft[operand];
        }
        order.push_back(id);
        done[id] = 1;
        for (int reader : readers[id])
            if (--operandsLeft[reader] == 0) ready.push_back(reader);
    }
    for (int root : roots)  // a leaf that is itself a result
        if (!done[root]) {
            order.push_back(root);
            done[root] = 1;
        }
    return order;
}

}  // namespace

Program compile(const Expression& e, const std::vector<int>& roots) {
    const std::vector<int> order = schedule(e, roots);

    // The position in `order` of each node's last reader; roots live to the end.
    constexpr int kForever = std::numeric_limits<int>::max();
    std::vector<int> lastUse(e.size(), -1);
    for (size_t k = 0; k < order.size(); ++k) {
        const Node& n = e.node(order[k]);
        for (int operand : {n.a, n.b, n.c})
            if (operand >= 0) lastUse[operand] = static_cast<int>(k);
    }
    for (int root : roots) lastUse[root] = kForever;

    Program program;
    program.outputs = static_cast<int>(roots.size());
    std::vector<int> registerOf(e.size(), -1);
    std::vector<char> busy(kMaxRegisters, 0);
    std::map<double, int> constantSlot;
    for (size_t k = 0; k < order.size(); ++k) {
        const int id = order[k];
        const Node& n = e.node(id);
        Instruction in{};
        switch (n.op) {
            case Op::constant: {
                auto [slot, added] = constantSlot.emplace(n.value, static_cast<int>(program.constants.size()));
                if (added) program.constants.push_back(n.value);
                if (program.constants.size() > static_cast<size_t>(kMaxConstants))
                    throw ExpressionError(0, "the expression has more than " + std::to_string(kMaxConstants) +
                                                 " distinct numbers");
                in.op = Op::constant;
                in.a = small(slot->second);
                break;
            }
            case Op::input:
            case Op::column:
                in.op = n.op;
                in.a = small(n.index);
                break;
            default:
                in.op = n.op;
                in.a = small(registerOf[n.a]);
                in.b = small(n.b >= 0 ? registerOf[n.b] : registerOf[n.a]);
                in.c = small(n.c >= 0 ? registerOf[n.c] : registerOf[n.a]);
                in.exponent = static_cast<int8_t>(n.op == Op::powi ? n.index : 0);
                break;
        }
        // Operands read for the last time free their registers before the result takes one.
        for (int operand : {n.a, n.b, n.c})
            if (operand >= 0 && lastUse[operand] == static_cast<int>(k)) busy[registerOf[operand]] = 0;
        const auto free = std::find(busy.begin(), busy.end(), 0);
        if (free == busy.end())
            throw ExpressionError(0, "the expression needs more than " + std::to_string(kMaxRegisters) +
                                         " intermediate values at once");
        const int reg = static_cast<int>(free - busy.begin());
        busy[reg] = lastUse[id] >= 0 ? 1 : 0;
        registerOf[id] = reg;
        in.dst = small(reg);
        program.registers = std::max(program.registers, reg + 1);
        program.code.push_back(in);
    }
    for (size_t k = 0; k < roots.size(); ++k) {
        Instruction out{};
        out.op = Op::output;
        out.dst = small(static_cast<int>(k));
        out.a = small(registerOf[roots[k]]);
        program.code.push_back(out);
    }
    return program;
}

std::vector<double> Program::run(const std::vector<double>& inputs, const std::vector<double>& columns) const {
    const ProgramView<double> view{code.data(), constants.data(), static_cast<int>(code.size())};
    std::vector<double> out(outputs);
    run_program(view, inputs.data(), columns.data(), out.data());
    return out;
}

}  // namespace structmd::expression
