#pragma once
// Which engine a handle builds: the backend and the precision, as enums inside the engine; their
// names are only for the options, get_info and messages.
#include <string>

namespace structmd {

enum class BackendKind { cpu, cuda };

// single: everything in float; mixed: state and sums in double, pair potentials in float; double.
enum class Precision { single, mixed, double_ };

inline const char* name_of(BackendKind backend) { return backend == BackendKind::cuda ? "cuda" : "cpu"; }
inline const char* name_of(Precision precision) {
    switch (precision) {
        case Precision::single: return "single";
        case Precision::mixed: return "mixed";
        case Precision::double_: return "double";
    }
    return "single";
}

}  // namespace structmd
