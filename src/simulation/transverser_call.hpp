#pragma once
// A registered transverser (transverser/transverser_component.hpp) as the engine is asked to run it
// (SimulationProbes::traverse): which one, from which plugin, its parameters, the traversal (a
// neighbour list of a cutoff, or all pairs) and the group. Backend-free: the API makes it from the
// host's arguments; the engine finds the plugin's runner for its own backend and precision.
#include <memory>
#include <string>

#include "core/parameters.hpp"

namespace structmd {

struct ComponentSet;

struct TransverserCall {
    std::string name;
    std::shared_ptr<const ComponentSet> source;  // the plugin that registered it
    ParameterValues parameters;
    int values = 1;             // numbers per particle
    double cutoff = 0;          // > 0: pairs closer than this over a neighbour list; 0: all pairs
    std::string group = "All";  // the force field's group whose particles take part (both of a pair)
    std::string path;           // where the group was given, for messages
};

}  // namespace structmd
