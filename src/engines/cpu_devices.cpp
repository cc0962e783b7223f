// The CPU side of devices.hpp.
#include <omp.h>

#include "engines/devices.hpp"

namespace structmd {

int cpu_default_threads() { return omp_get_max_threads(); }

}  // namespace structmd
