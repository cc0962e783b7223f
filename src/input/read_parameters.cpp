#include "input/read_parameters.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace structmd::input {

void check_rule(const TrackedNode& node, double value, Must must, const std::string& what) {
    const auto fail = [&](const std::string& expected) { return input_error(node.path(), "expected " + expected); };
    if (!std::isfinite(value)) throw fail("a finite " + what);
    switch (must) {
        case Must::be_finite:
        case Must::be_boolean: break;
        case Must::be_positive:
            if (!(value > 0.0)) throw fail("a positive " + what);
            break;
        case Must::be_non_negative:
            if (!(value >= 0.0)) throw fail("a " + what + " >= 0");
            break;
        case Must::be_integer:
            if (value != std::floor(value)) throw fail("an integer");
            break;
        case Must::be_positive_integer:
            if (!(value >= 1.0) || value != std::floor(value)) throw fail("an integer >= 1");
            break;
        case Must::be_at_least_one:
            if (!(value >= 1.0)) throw fail("a " + what + " >= 1");
            break;
    }
}

namespace {

double checked(const TrackedNode& node, Must must) {
    if (must == Must::be_boolean) return node.as<bool>() ? 1.0 : 0.0;
    const double value = node.as<double>();
    check_rule(node, value, must);
    return value;
}

}  // namespace

std::vector<double> read_parameter(const TrackedNode& node, const Parameter& parameter) {
    if (parameter.size == 1) return {checked(node, parameter.must)};
    if (!node.is_array() || node.size() != static_cast<size_t>(parameter.size))
        throw input_error(node.path(), "expected a list of " + std::to_string(parameter.size) + " numbers");
    std::vector<double> values;
    for (int k = 0; k < parameter.size; ++k) values.push_back(checked(node.at(k), parameter.must));
    return values;
}

TrackedNode parameters_of(const TrackedNode& entry) {
    auto params = entry.find("parameters");
    if (!params) return TrackedNode();
    if (!params->is_object()) throw input_error(params->path(), "expected an object of parameters");
    return *params;
}

ParameterValues read_parameters(const TrackedNode& entry, const std::vector<Parameter>& schema) {
    return read_parameter_object(parameters_of(entry), entry.path() + ".parameters", schema);
}

ParameterValues read_parameter_object(const TrackedNode& params, const std::string& path,
                                      const std::vector<Parameter>& schema) {
    ParameterValues values;
    for (const Parameter& p : schema) {
        auto node = params.valid() ? params.find(p.name) : std::nullopt;
        if (node)
            values.set(p.name, read_parameter(*node, p));
        else if (p.required())
            throw params.valid() ? params.missing(p.name, "missing required parameter")
                                 : input_error(path + "." + p.name, "missing required parameter");
        else
            values.set(p.name, std::vector<double>(p.size, p.fallback));
    }
    return values;
}

std::string text_option_names(const TextOption& option) {
    std::string names;
    for (const auto* list : {&option.supported, &option.unsupported})
        for (const std::string& n : *list) names += (names.empty() ? "" : ", ") + n;
    return names;
}

size_t choose_text_option(const TextOption& option, const std::string& value, const std::string& path) {
    for (size_t k = 0; k < option.supported.size(); ++k)
        if (option.supported[k] == value) return k;
    if (std::find(option.unsupported.begin(), option.unsupported.end(), value) != option.unsupported.end())
        throw Error(STRUCTMD_ERR_UNSUPPORTED, path + ": \"" + value + "\" is not supported: " + option.why_unsupported);
    throw input_error(path, "expected one of " + text_option_names(option) + ", got \"" + value + "\"");
}

}  // namespace structmd::input
