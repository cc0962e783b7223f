#include "engines/make_engine.hpp"

#include "core/error.hpp"
#include "engines/engine_instances.hpp"
#include "simulation/read_simulation.hpp"

namespace structmd {

std::unique_ptr<Simulation> load_simulation(const EngineOptions& options, const std::string& text,
                                            const ForceFieldComponents& components, const Logger& log,
                                            int64_t firstParticleId) {
    SimulationSpec spec = read_simulation(text, log, components.reader());
    spec.firstParticleId = firstParticleId;
    return make_simulation(options, std::move(spec), components, log);
}

std::unique_ptr<Simulation> make_simulation(const EngineOptions& options, SimulationSpec spec,
                                            const ForceFieldComponents& components, const Logger& log) {
    if (options.backend == BackendKind::cuda) {
        switch (options.precision) {
            case Precision::single: return make_cuda_engine_single(options.device, std::move(spec), components, log);
            case Precision::mixed: return make_cuda_engine_mixed(options.device, std::move(spec), components, log);
            case Precision::double_: return make_cuda_engine_double(options.device, std::move(spec), components, log);
        }
    }
    switch (options.precision) {
        case Precision::single: return make_cpu_engine_single(options.threads, std::move(spec), components, log);
        case Precision::mixed: return make_cpu_engine_mixed(options.threads, std::move(spec), components, log);
        case Precision::double_: return make_cpu_engine_double(options.threads, std::move(spec), components, log);
    }
    throw Error(STRUCTMD_ERR_INTERNAL, "no engine for the options given");
}

}  // namespace structmd
