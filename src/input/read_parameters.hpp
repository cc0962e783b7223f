#pragma once
// Reading a component's declared parameters (core/parameters.hpp) from JSON, with the rule of each
// checked and the path of the culprit in every message.
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "input/tracked_node.hpp"

namespace structmd::input {

// Throws an input error at the node's path unless `value` is finite and keeps `must`; `what` names
// the kind of value in the message ("expected a positive number").
void check_rule(const TrackedNode& node, double value, Must must, const std::string& what = "number");

// The numbers of one parameter: a number, or a list of `size` numbers.
std::vector<double> read_parameter(const TrackedNode& node, const Parameter& parameter);

// The "parameters" object of an entry, or an invalid node when it has none; a "parameters" that is
// not an object is an error.
TrackedNode parameters_of(const TrackedNode& entry);

// The parameters in `schema` from the entry's "parameters" object; absent ones take their default,
// and an absent required one is an error naming <entry>.parameters.<name>.
ParameterValues read_parameters(const TrackedNode& entry, const std::vector<Parameter>& schema);
// The same from an object of parameters itself (`params`), which may sit anywhere; invalid when none
// was given, and then `path` is where an absent required one is named (<path>.<name>).
ParameterValues read_parameter_object(const TrackedNode& params, const std::string& path,
                                      const std::vector<Parameter>& schema);

// The index among option.supported of a named choice's value, given at `path`: ERR_UNSUPPORTED for a
// name the reference defines and structmd does not, an input error for any other.
size_t choose_text_option(const TextOption& option, const std::string& value, const std::string& path);
// Every name of the option, supported first: "none, LLG_Euler, LLG_Heun".
std::string text_option_names(const TextOption& option);

}  // namespace structmd::input
