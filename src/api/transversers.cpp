// Transversers from the host: an expression transverser run once (SimulationProbes::expression_sum).
#include <string>

#include "api/handle.hpp"
#include "simulation/expression_transverser.hpp"

using namespace structmd;
using namespace structmd::api;

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

}  // extern "C"
