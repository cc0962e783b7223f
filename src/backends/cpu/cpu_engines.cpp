// The CPU backend's entry points; the engines themselves are instantiated in cpu_engine_single.cpp
// cpu_engine_mixed.cpp and cpu_engine_double.cpp.
#include <omp.h>

#include "backends/backend_engines.hpp"

namespace structmd {

std::unique_ptr<Simulation> make_cpu_engine(const std::string& precision, int threads, SimulationSpec spec,
                                            const Logger& log) {
    if (precision == "double") return make_cpu_engine_double(threads, std::move(spec), log);
    if (precision == "mixed") return make_cpu_engine_mixed(threads, std::move(spec), log);
    return make_cpu_engine_single(threads, std::move(spec), log);
}

int cpu_default_threads() { return omp_get_max_threads(); }

}  // namespace structmd
