#pragma once
// Parameters by name. A component declares the parameters it reads (its schema: name, size, rule,
// default, units); the input layer reads them from JSON into ParameterValues; the component's
// make_params takes the values by name. There is no positional array to get out of order, and a
// name the component asks for but never declared is an internal error, not a silent zero.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace structmd {

// What a parameter's numbers must be, beyond finite.
enum class Must { be_finite, be_positive, be_non_negative, be_integer, be_positive_integer, be_at_least_one, be_boolean };

struct Parameter {
    const char* name;
    int size = 1;  // 3 for a vector, 4 for Dihedral4's K, ...
    Must must = Must::be_finite;
    double fallback = std::numeric_limits<double>::quiet_NaN();  // NaN: required
    const char* units = "";  // what the number measures, for the docs ("energy", "length", "1/time", ...)

    bool required() const { return std::isnan(fallback); }
};

// A parameter whose value is a name: those structmd computes, and those the reference defines but
// structmd does not (refused with the reason; any other name is an input error).
struct TextOption {
    const char* name;
    const char* fallback;  // the value when absent
    std::vector<std::string> supported;
    std::vector<std::string> unsupported;
    const char* why_unsupported = "";
};

inline constexpr double kRequired = std::numeric_limits<double>::quiet_NaN();

// A required number, a required vector of three, and a parameter with a default.
inline Parameter number(const char* name, const char* units, Must must = Must::be_finite) {
    return {name, 1, must, kRequired, units};
}
inline Parameter numbers(const char* name, int size, const char* units, Must must = Must::be_finite) {
    return {name, size, must, kRequired, units};
}
// true or false in the input, 1 or 0 in the values.
inline Parameter boolean(const char* name) { return {name, 1, Must::be_boolean, kRequired, "true/false"}; }
inline Parameter with_default(Parameter p, double fallback) {
    p.fallback = fallback;
    return p;
}

// Numbers a row of the schema takes (the sum of the sizes).
inline int width_of(const std::vector<Parameter>& schema) {
    int width = 0;
    for (const Parameter& p : schema) width += p.size;
    return width;
}

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

    // A vector parameter of three numbers (a position, a force).
    std::array<double, 3> vec3(const std::string& name) const {
        const std::vector<double>& held = vector(name);
        if (held.size() != 3)
            throw Error(STRUCTMD_ERR_INTERNAL, "parameter '" + name + "' holds " + std::to_string(held.size()) +
                                                   " numbers, asked for three");
        return {held[0], held[1], held[2]};
    }

    // Sets every parameter of `schema` from `flat`, laid out in the schema's order (a parameter of
    // size k takes k numbers). Reuses the storage: a bond table fills one object per bond.
    void assign(const std::vector<Parameter>& schema, const double* flat) {
        values_.resize(schema.size());
        for (size_t k = 0; k < schema.size(); ++k) {
            values_[k].first = schema[k].name;
            values_[k].second.assign(flat, flat + schema[k].size);
            flat += schema[k].size;
        }
    }

    const std::vector<std::pair<std::string, std::vector<double>>>& all() const { return values_; }

private:
    std::vector<std::pair<std::string, std::vector<double>>> values_;
};

// The values of `schema` from numbers laid out in its order.
inline ParameterValues values_in_order(const std::vector<Parameter>& schema, const double* flat) {
    ParameterValues values;
    values.assign(schema, flat);
    return values;
}

}  // namespace structmd
