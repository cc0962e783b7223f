#pragma once
// Which engine a handle builds: the backend and the precision, as enums inside the engine; their
// names are only for the options, get_info and messages.
#include <string>
#include <vector>

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

// Whether this build has the engines of a precision (CMake STRUCTMD_PRECISIONS, all three by default).
constexpr bool precision_compiled(Precision precision) {
    switch (precision) {
        case Precision::single:
#ifdef STRUCTMD_WITH_SINGLE
            return true;
#else
            return false;
#endif
        case Precision::mixed:
#ifdef STRUCTMD_WITH_MIXED
            return true;
#else
            return false;
#endif
        case Precision::double_:
#ifdef STRUCTMD_WITH_DOUBLE
            return true;
#else
            return false;
#endif
    }
    return false;
}

// The names of the precisions this build has, single to double.
inline std::vector<std::string> compiled_precisions() {
    std::vector<std::string> names;
    for (Precision precision : {Precision::single, Precision::mixed, Precision::double_})
        if (precision_compiled(precision)) names.push_back(name_of(precision));
    return names;
}

// A handle's precision when its options name none: single, or the first of mixed and double that a
// build limited by STRUCTMD_PRECISIONS has.
constexpr Precision default_precision() {
    if (precision_compiled(Precision::single)) return Precision::single;
    return precision_compiled(Precision::mixed) ? Precision::mixed : Precision::double_;
}

}  // namespace structmd
