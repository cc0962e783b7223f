// Transversers from the host: an expression transverser run once (SimulationProbes::expression_sum),
// and a transverser a plugin registered, run once by name, its values copied to the host
// (SimulationProbes::traverse) or lent as a DLPack tensor (SimulationProbes::traverse_on_backend).
// A host that runs the same transverser call after call has its parameters read once.
#include <string>

#include "api/dlpack_tensor.hpp"
#include "api/handle.hpp"
#include "simulation/expression_transverser.hpp"
#include "simulation/transverser_call.hpp"

using namespace structmd;
using namespace structmd::api;

namespace {

// make_transverser_call, or the handle's last call when the arguments are the same.
const TransverserCall& transverser_call(structmd_sim& s, const char* name, const char* parameters, double cutoff) {
    auto& last = s.lastTransverser;
    const char* given = parameters ? parameters : "";
    // A NaN cutoff never equals the last one, so it reaches the check that refuses it.
    if (!last.call || last.name != name || last.parameters != given || !(last.cutoff == cutoff)) {
        last.call.reset();
        last.call = std::make_unique<const TransverserCall>(make_transverser_call(*s.components, name, parameters, cutoff));
        last.name = name;
        last.parameters = given;
        last.cutoff = cutoff;
    }
    return *last.call;
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
        *values = transverser_values(*s.components, name);
    });
}

structmd_status structmd_traverse(structmd_sim* sim, const char* name, const char* parameters, double cutoff,
                                  double* out, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(name, "name");
        const TransverserCall& call = transverser_call(s, name, parameters, cutoff);
        const int64_t expected = simulation.particle_count() * call.values;
        if (n != expected)
            throw Error(STRUCTMD_ERR_ARGUMENT, "n: expected " + std::to_string(expected) + " (" +
                                                   std::to_string(call.values) + " per particle for transverser '" +
                                                   call.name + "'), got " + std::to_string(n));
        require_pointer(out, "out");
        simulation.probes().traverse(call, out);
    });
}

structmd_status structmd_traverse_view(structmd_sim* sim, const char* name, const char* parameters, double cutoff,
                                       structmd_dlpack_tensor** view) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(name, "name");
        require_pointer(view, "view");
        const TransverserCall& call = transverser_call(s, name, parameters, cutoff);
        const SimulationProbes::TransverserOutput output = simulation.probes().traverse_on_backend(call);
        // One value per particle is a vector, as Python's Simulation.traverse gives it.
        const int ndim = output.values == 1 ? 1 : 2;
        const int64_t shape[2] = {output.n, output.values};
        const int64_t strides[2] = {ndim == 1 ? 1 : output.values, 1};
        *view = make_engine_tensor(output.data, output.device, output.realSize, ndim, shape, strides);
    });
}

}  // extern "C"
