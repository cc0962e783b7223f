#pragma once
// Parameters by name. A component declares the parameters it reads (its schema: name, size, rule,
// default, units); the input layer reads them from JSON into ParameterValues; the component's
// make_params takes the values by name. There is no positional array to get out of order, and a
// name the component asks for but never declared is an internal error, not a silent zero.
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace structmd {

// What a parameter's numbers must be, beyond finite.
enum class Must { be_finite, be_positive, be_non_negative, be_integer, be_at_least_one };

struct Parameter {
    const char* name;
    int size = 1;  // 3 for a vector, 4 for Dihedral4's K, ...
    Must must = Must::be_finite;
    double fallback = std::numeric_limits<double>::quiet_NaN();  // NaN: required
    const char* units = "";  // what the number measures, for the docs ("energy", "length", "1/time", ...)

    bool required() const { return std::isnan(fallback); }
};

inline constexpr double kRequired = std::numeric_limits<double>::quiet_NaN();

// Values read for one entry (or one row of an entry's table), by name.
class ParameterValues {
public:
    void set(std::string name, std::vector<double> values) {
        for (auto& [key, held] : values_)
            if (key == name) {
                held = std::move(values);
                return;
            }
        values_.emplace_back(std::move(name), std::move(values));
    }

    const std::vector<double>& vector(const std::string& name) const {
        for (const auto& [key, held] : values_)
            if (key == name) return held;
        throw Error(STRUCTMD_ERR_INTERNAL, "parameter '" + name + "' was asked for but not declared");
    }

    double operator[](const std::string& name) const {
        const std::vector<double>& held = vector(name);
        if (held.size() != 1)
            throw Error(STRUCTMD_ERR_INTERNAL, "parameter '" + name + "' holds " + std::to_string(held.size()) +
                                                   " numbers, asked for one");
        return held[0];
    }

    const std::vector<std::pair<std::string, std::vector<double>>>& all() const { return values_; }

private:
    std::vector<std::pair<std::string, std::vector<double>>> values_;
};

}  // namespace structmd
