#pragma once
// The state's optional per-particle numbers, each declared once here: its label in the state table,
// what its values must be, and whether the engine keeps it on the backend. The reader fills a column
// only when the state table has it (empty otherwise); the engine uploads the backend's ones and a
// subset or a domain takes its particles' values. A new column is one row in each list below and
// the code that reads it.
#include <array>
#include <cstddef>

namespace structmd {

enum class StateColumn : int {
    polarizability,              // induced dipoles of ["External","PolarizationTabulated"]
    innerRadius,                 // the size in ["NonBonded","StericInner6"/"StericInner12"]
    frictionConstant,            // Langevin: gamma by particle where the integrator gives none
    translationalSelfDiffusion,  // Brownian: D by particle where the integrator gives no viscosity
    rotationalSelfDiffusion,     // rigid-body Brownian: D_r by particle, likewise
    anisotropy,                  // magnetic: the anisotropy constant K (energy/volume)
};
inline constexpr int kStateColumns = 6;

enum class ColumnValues { anyNumber, atLeastZero, positive };

struct StateColumnTraits {
    const char* label;
    ColumnValues values;
    bool onBackend;  // read by kernels; the others are read by the components' readers on the host
};

inline const StateColumnTraits& traits(StateColumn c) {
    static constexpr StateColumnTraits kTable[kStateColumns] = {
        {"polarizability", ColumnValues::anyNumber, false},
        {"innerRadius", ColumnValues::atLeastZero, false},
        {"frictionConstant", ColumnValues::positive, true},
        {"translationalSelfDiffusion", ColumnValues::positive, true},
        {"rotationalSelfDiffusion", ColumnValues::positive, true},
        {"anisotropy", ColumnValues::anyNumber, true},
    };
    static_assert(sizeof(kTable) / sizeof(kTable[0]) == kStateColumns, "one row per column");
    return kTable[static_cast<int>(c)];
}

// One T per column, indexed by the column.
template <class T>
struct PerStateColumn {
    std::array<T, kStateColumns> values{};
    T& operator[](StateColumn c) { return values[static_cast<size_t>(c)]; }
    const T& operator[](StateColumn c) const { return values[static_cast<size_t>(c)]; }
};

// f(column) for each column.
template <class F>
void for_each_state_column(F&& f) {
    for (int k = 0; k < kStateColumns; ++k) f(StateColumn(k));
}

}  // namespace structmd
