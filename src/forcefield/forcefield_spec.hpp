#pragma once
// The force field as read from topology.forceField: plain data, validated against the system, with
// the JSON path of each entry kept for later messages. The engine turns it into interactors.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace structmd {

// A named selection of particles (["Groups","GroupsList"]); "All" is every particle.
struct GroupSpec {
    std::string name;
    std::vector<uint8_t> members;  // by particle id: 1 in the group
};

// The index of the group called `name` (-1 for "All", every particle); an input error at `path` when
// no group has that name. Every component that takes a "group" parameter looks it up here.
inline int group_index(const std::vector<GroupSpec>& groups, const std::string& name, const std::string& path) {
    if (name == "All") return -1;
    for (size_t g = 0; g < groups.size(); ++g)
        if (groups[g].name == name) return static_cast<int>(g);
    throw input_error(path, "no group named '" + name + "' (define it in a [\"Groups\", \"GroupsList\"] entry)");
}

// What every interaction entry shares: its name, where it was read, when it is active
// (startStep <= step < endStep) and which particles it acts on.
struct InteractionSpec {
    std::string name;
    std::string path;
    std::string potential;  // the family, e.g. "Harmonic" for Harmonic, HarmonicCommon_K, ...
    int64_t startStep = 0;
    int64_t endStep = std::numeric_limits<int64_t>::max();
    int group = -1;  // index into ForceFieldSpec::groups; -1: all particles
};

struct NeighbourListSpec {
    std::string name;
    std::string path;
    std::string condition;  // "all", "nonExcluded" or "intra_inter"
    double verletFactor = 1.1;
    double minimumCutoff = 0.0;            // the entry's cutOff parameter
    std::vector<std::vector<int>> excluded;  // nonExcluded: by particle id, sorted ids never paired
};

struct PairSpec : InteractionSpec {
    struct Row {
        int typeI, typeJ;
        double epsilon, sigma;
    };
    std::string subList;  // "all", "nonExcluded", "intra" or "inter"
    int list = 0;         // index into ForceFieldSpec::lists
    double cutOffFactor = 0.0;
    bool shift = false;
    std::vector<Row> rows;       // each unordered type pair at most once (table potentials)
    double dielectricConstant = 1.0;  // Debye-Hueckel
    double debyeLength = 1.0;

    double largest_cutoff() const;
};

struct BondSpec : InteractionSpec {
    int arity = 2;
    int parameterCount = 0;
    std::vector<int> members;    // arity particle ids per bond
    std::vector<double> params;  // parameterCount values per bond, in the potential's order
};

struct ExternalSpec : InteractionSpec {
    std::vector<double> values;  // the potential's parameters, in its order
};

struct ForceFieldSpec {
    std::vector<GroupSpec> groups;
    std::vector<NeighbourListSpec> lists;
    std::vector<PairSpec> pairs;
    std::vector<BondSpec> bonds;
    std::vector<ExternalSpec> externals;
    std::vector<std::string> entryNames;  // every interaction entry (energy terms), in document order
};

}  // namespace structmd
