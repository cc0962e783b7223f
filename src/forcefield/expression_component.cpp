// Reading an Expression entry: its energy text parsed against the entry's inputs, data columns and
// parameters, differentiated and compiled (expression_component.hpp).
#include "forcefield/expression_component.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "expression/derivative.hpp"
#include "expression/parser.hpp"
#include "forcefield/component_registry.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

using expression::Binding;
using expression::ExpressionError;

namespace {

// The variables each kind of Expression entry is a function of, and how many of them (the first)
// the energy is differentiated against (t of an external field is not).
struct Inputs {
    std::vector<std::string> names;
    int differentiated;
};

Inputs inputs_of(InteractionKind kind, int arity) {
    if (kind == InteractionKind::external) return {{"x", "y", "z", "t"}, 3};
    if (kind == InteractionKind::pair || arity == 2) return {{"r"}, 1};
    return {{arity == 3 ? "theta" : "phi"}, 1};
}

// The labels of the entry's table that are not ids or type names: the candidates for data columns.
std::vector<std::pair<std::string, std::string>> value_labels(const input::ComponentEntry& entry) {
    std::vector<std::pair<std::string, std::string>> labels;  // name, path
    const std::optional<input::TrackedNode> node = entry.node.find("labels");
    if (!node || !node->is_array()) return labels;
    static const char* const structural[] = {"name_i", "name_j", "id_i", "id_j", "id_k", "id_l"};
    for (size_t k = 0; k < node->size(); ++k) {
        const input::TrackedNode label = node->at(k);
        if (!label.is_string()) continue;  // read_table names the culprit
        const std::string name = label.as<std::string>();
        if (std::find(std::begin(structural), std::end(structural), name) == std::end(structural))
            labels.emplace_back(name, label.path());
    }
    return labels;
}

ForceFieldComponent configure(const ForceFieldComponent& registered, const input::ComponentEntry& entry) {
    const Inputs inputs = inputs_of(registered.kind, registered.arity);
    const input::TrackedNode params = input::parameters_of(entry.node);
    if (!params.valid()) throw input_error(entry.node.path() + ".parameters.energy", "missing required parameter");
    const input::TrackedNode energy = params.at("energy");
    if (!energy.is_string()) throw input_error(energy.path(), "expected the energy as a text expression");
    const std::string text = energy.as<std::string>();

    auto config = std::make_shared<ExpressionConfig>();
    config->path = energy.path();
    config->inputs = inputs.names;
    const auto labels = value_labels(entry);
    const auto resolve = [&](const std::string& name) -> Binding {
        const auto input = std::find(inputs.names.begin(), inputs.names.end(), name);
        if (input != inputs.names.end()) return {Binding::Kind::input, static_cast<int>(input - inputs.names.begin()), 0};
        const bool isColumn = std::any_of(labels.begin(), labels.end(), [&](const auto& l) { return l.first == name; });
        const bool isParameter = name != "energy" && params.has(name);
        if (isColumn && isParameter)
            throw ExpressionError(0, "'" + name + "' is both a data column and a key of parameters");
        if (isParameter) {
            const input::TrackedNode value = params.at(name);
            input::check_rule(value, value.as<double>(), Must::be_finite);
            return {Binding::Kind::number, 0, value.as<double>()};
        }
        if (!isColumn) return {};
        auto slot = std::find(config->columns.begin(), config->columns.end(), name);
        if (slot == config->columns.end()) {
            if (config->columns.size() == static_cast<size_t>(expression::kMaxColumns))
                throw ExpressionError(0, "more than " + std::to_string(expression::kMaxColumns) + " data columns");
            slot = config->columns.insert(config->columns.end(), name);
        }
        return {Binding::Kind::column, static_cast<int>(slot - config->columns.begin()), 0};
    };
    try {
        const int root = expression::parse(text, resolve, config->graph);
        config->roots.push_back(root);
        for (int k = 0; k < inputs.differentiated; ++k)
            config->roots.push_back(expression::differentiate(config->graph, root, k));
        config->program = expression::compile(config->graph, config->roots);
    } catch (const ExpressionError& e) {
        std::string what = e.what();
        if (what.find("unknown variable") != std::string::npos) {
            std::string known;
            for (const std::string& name : inputs.names) known += (known.empty() ? "" : ", ") + name;
            what += " (not " + known + ", a column of \"labels\" or a key of \"parameters\")";
        }
        throw input_error(config->path, what);
    }
    for (const auto& [name, path] : labels)
        if (std::find(config->columns.begin(), config->columns.end(), name) == config->columns.end())
            throw input_error(path, "the data column '" + name + "' is not used by the energy expression");

    ForceFieldComponent c = registered;
    c.configure = nullptr;
    c.parameters.clear();
    for (const std::string& name : config->columns) c.parameters.push_back(number(name.c_str(), "as the expression"));
    if (c.kind == InteractionKind::pair) {
        const std::shared_ptr<const ExpressionConfig> shared = config;
        c.actingCutoff = [shared](const ParameterValues& v, const Constants&, double, bool shift) {
            const double cutOff = v["cutOff"];
            if (shift) {
                const std::vector<double> at = shared->program.run({cutOff}, shared->columns_of(v));
                if (!std::isfinite(at[0]) || !std::isfinite(at[1])) {
                    std::ostringstream what;
                    what.precision(17);
                    what << "the energy (" << at[0] << ") or its derivative (" << at[1]
                         << ") is not finite at the cut-off r = " << cutOff << ", where shift takes its value";
                    throw input_error(shared->path, what.str());
                }
            }
            return cutOff;
        };
    }
    c.config = std::move(config);
    return c;
}

}  // namespace

std::vector<double> ExpressionConfig::columns_of(const ParameterValues& values) const {
    std::vector<double> numbers;
    for (const std::string& name : columns) numbers.push_back(values[name]);
    return numbers;
}

const ExpressionConfig& expression_config(const InteractionSpec& spec) {
    const auto* config = dynamic_cast<const ExpressionConfig*>(spec.config.get());
    if (!config) throw Error(STRUCTMD_ERR_INTERNAL, spec.path + ": an Expression entry was read without its expression");
    return *config;
}

namespace {

ForceFieldComponent expression_reader_entry(ComponentKey key, InteractionKind kind, int arity) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = kind;
    c.arity = arity;
    c.underDomains = kind == InteractionKind::bond && arity == 2;  // an expression of r reads two positions
    if (kind == InteractionKind::pair) {
        c.entryParameters = {number("cutOff", "length", Must::be_positive)};
        c.readsCutOffFactor = false;
    }
    c.configure = [c](const input::ComponentEntry& entry, const input::SystemDescription&) { return configure(c, entry); };
    return c;
}

}  // namespace

ForceFieldComponent ExpressionPairComponent::reader_entry(ComponentKey key) {
    return expression_reader_entry(std::move(key), InteractionKind::pair, 0);
}

template <int N>
ForceFieldComponent ExpressionBondComponent<N>::reader_entry(ComponentKey key) {
    return expression_reader_entry(std::move(key), InteractionKind::bond, N);
}
template ForceFieldComponent ExpressionBondComponent<2>::reader_entry(ComponentKey);
template ForceFieldComponent ExpressionBondComponent<3>::reader_entry(ComponentKey);
template ForceFieldComponent ExpressionBondComponent<4>::reader_entry(ComponentKey);

ForceFieldComponent ExpressionExternalComponent::reader_entry(ComponentKey key) {
    return expression_reader_entry(std::move(key), InteractionKind::external, 0);
}

}  // namespace structmd
