#include "engines/make_engine.hpp"

#include "core/error.hpp"
#include "engines/engine_instances.hpp"
#include "simulation/read_simulation.hpp"

namespace structmd {

std::unique_ptr<LocalEngine> load_simulation(const EngineOptions& options, const std::string& text,
                                            const ForceFieldComponents& components, const Logger& log,
                                            int64_t firstParticleId) {
    SimulationSpec spec = read_simulation(text, log, components.reader());
    spec.firstParticleId = firstParticleId;
    return make_simulation(options, std::move(spec), components, log);
}

std::unique_ptr<LocalEngine> make_simulation(const EngineOptions& options, SimulationSpec spec,
                                            const ForceFieldComponents& components, const Logger& log) {
    const bool cuda = options.backend == BackendKind::cuda;
    spec.forceField.clusterPairs = cluster_pairs(options);
    spec.stepGraphs = options.stepGraphs;
#ifdef STRUCTMD_WITH_SINGLE
    if (options.precision == Precision::single)
        return cuda ? make_cuda_engine_single(options.device, std::move(spec), components, log)
                    : make_cpu_engine_single(options.threads, std::move(spec), components, log);
#endif
#ifdef STRUCTMD_WITH_MIXED
    if (options.precision == Precision::mixed)
        return cuda ? make_cuda_engine_mixed(options.device, std::move(spec), components, log)
                    : make_cpu_engine_mixed(options.threads, std::move(spec), components, log);
#endif
#ifdef STRUCTMD_WITH_DOUBLE
    if (options.precision == Precision::double_)
        return cuda ? make_cuda_engine_double(options.device, std::move(spec), components, log)
                    : make_cpu_engine_double(options.threads, std::move(spec), components, log);
#endif
    // parse_engine_options already refused a precision the build lacks.
    throw Error(STRUCTMD_ERR_INTERNAL, "no engine for the options given");
}

}  // namespace structmd
