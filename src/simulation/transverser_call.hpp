#pragma once
// A registered transverser (transverser/transverser_component.hpp) as the engine is asked to run it
// (SimulationProbes::traverse): which one, from which plugin, its parameters, the traversal (a
// neighbour list of a cutoff, or all pairs) and the group. Backend-free: made from the host's
// arguments (structmd_traverse); the engine finds the plugin's runner for its backend and precision.
#include <memory>
#include <string>

#include "core/parameters.hpp"

namespace structmd {

namespace input {
class TrackedNode;
}
struct ComponentSet;
class ForceFieldComponents;

struct TransverserCall {
    std::string name;
    std::shared_ptr<const ComponentSet> source;  // the plugin that registered it
    ParameterValues parameters;
    int values = 1;             // numbers per particle
    double cutoff = 0;          // > 0: pairs closer than this over a neighbour list; 0: all pairs
    std::string group = "All";  // the force field's group whose particles take part (both of a pair)
    std::string path;           // where the group was given, for messages
};

// The call of transverser `name`, registered by one of `components`' plugins, with the host's
// `parameters`: NULL, "" or a JSON object of its named parameters and, optionally, "group" (a group
// of the force field). An unknown name, or parameters that are not a JSON object, is ERR_ARGUMENT; a
// parameter it does not take, one breaking its rule or a negative or non-finite cutoff ERR_INPUT,
// named as "<name>.parameters.<parameter>".
TransverserCall make_transverser_call(const ForceFieldComponents& components, const std::string& name,
                                      const char* parameters, double cutoff);

// The same from `parameters`, the object of its named parameters as a reader found it (invalid: none
// given), whose path names the errors (<path>.<parameter>; `path` for a required one when none was
// given). Every key of the object must be one of its parameters. The group is every particle; the
// cutoff, >= 0 and finite, is the caller's to check.
TransverserCall make_transverser_call(const ForceFieldComponents& components, const std::string& name,
                                      const input::TrackedNode& parameters, const std::string& path, double cutoff);

// The values per particle of transverser `name`; ERR_ARGUMENT for an unknown name.
int transverser_values(const ForceFieldComponents& components, const std::string& name);

}  // namespace structmd
