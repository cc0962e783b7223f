// Transversers from the host: an expression transverser run once (SimulationProbes::expression_sum),
// and a transverser a plugin registered, run once by name (SimulationProbes::traverse).
#include <cmath>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "api/handle.hpp"
#include "forcefield/component_set.hpp"
#include "input/read_parameters.hpp"
#include "input/tracked_node.hpp"
#include "simulation/expression_transverser.hpp"
#include "simulation/transverser_call.hpp"

using namespace structmd;
using namespace structmd::api;

namespace {

// The call of transverser `name` with the host's parameters: a JSON object of its named parameters
// and, optionally, "group" (a group of the force field, as the force field's entries name one).
// Messages name the parameter as "<name>.parameters.<parameter>".
TransverserCall make_call(const structmd_sim& s, const std::string& name, const char* parameters, double cutoff) {
    auto [source, entry] = s.components->transverser(name);
    auto state = std::make_shared<input::TrackingState>();
    nlohmann::json& doc = state->document;
    doc = nlohmann::json::object();
    if (parameters && *parameters) {
        try {
            doc["parameters"] = nlohmann::json::parse(parameters);
        } catch (const nlohmann::json::exception& e) {
            throw Error(STRUCTMD_ERR_ARGUMENT, std::string("parameters: not valid JSON: ") + e.what());
        }
        if (!doc["parameters"].is_object()) throw Error(STRUCTMD_ERR_ARGUMENT, "parameters: expected a JSON object");
    }
    const input::TrackedNode root(state, &doc, name);
    TransverserCall call;
    call.name = name;
    call.values = entry->values;
    call.parameters = input::read_parameters(root, entry->parameters);
    const input::TrackedNode given = input::parameters_of(root);
    if (given.valid()) {
        if (auto group = given.find("group")) {
            call.group = group->as<std::string>();
            call.path = group->path();
        }
        given.check_all_used();
    }
    if (!(cutoff >= 0) || !std::isfinite(cutoff))
        throw input_error("cutoff", "expected a finite number >= 0 (0: all pairs), got " + std::to_string(cutoff));
    call.cutoff = cutoff;
    call.source = std::move(source);
    return call;
}

}  // namespace

extern "C" {

structmd_status structmd_traverse_expression(structmd_sim* sim, const char* compute, double cutoff, double* sums,
                                             int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(compute, "compute");
        require_count(simulation, n, sums, "sums");
        const ExpressionTransverserSpec spec = make_expression_transverser(compute, "compute", cutoff, -1);
        simulation.probes().expression_sum(spec, sums);
    });
}

structmd_status structmd_transverser_values(structmd_sim* sim, const char* name, int* values) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_pointer(name, "name");
        require_pointer(values, "values");
        *values = s.components->transverser(name).second->values;
    });
}

structmd_status structmd_traverse(structmd_sim* sim, const char* name, const char* parameters, double cutoff,
                                  double* out, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(name, "name");
        const TransverserCall call = make_call(s, name, parameters, cutoff);
        const int64_t expected = simulation.particle_count() * call.values;
        if (n != expected)
            throw Error(STRUCTMD_ERR_ARGUMENT, "n: expected " + std::to_string(expected) + " (" +
                                                   std::to_string(call.values) + " per particle for transverser '" +
                                                   call.name + "'), got " + std::to_string(n));
        require_pointer(out, "out");
        simulation.probes().traverse(call, out);
    });
}

}  // extern "C"
