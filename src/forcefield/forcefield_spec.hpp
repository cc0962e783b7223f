#pragma once
// The force field as read from topology.forceField: plain data, validated against the system, with
// the JSON path of each entry kept for later messages. The engine turns it into interactors.
#include <string>
#include <vector>


namespace structmd {

struct NeighbourListSpec {
    std::string name;
    std::string path;
    std::string condition;  // "all"
    double verletFactor = 1.1;
    double minimumCutoff = 0.0;  // the entry's cutOff parameter
};

struct PairSpec {
    struct Row {
        int typeI, typeJ;
        double epsilon, sigma;
    };
    std::string name;
    std::string path;
    std::string potential;  // SubClass, e.g. "LennardJonesType1"
    std::string condition;
    int list = 0;  // index into ForceFieldSpec::lists
    double cutOffFactor = 0.0;
    bool shift = false;
    std::vector<Row> rows;  // each unordered type pair at most once

    double largest_cutoff() const;
};

struct BondSpec {
    std::string name;
    std::string path;
    std::string potential;  // e.g. "Harmonic"
    int arity = 2;
    int parameterCount = 0;
    std::vector<int> ends;         // arity particle ids per bond
    std::vector<double> params;    // parameterCount values per bond
};

struct ForceFieldSpec {
    std::vector<NeighbourListSpec> lists;
    std::vector<PairSpec> pairs;
    std::vector<BondSpec> bonds;
    std::vector<std::string> entryNames;  // every interaction entry (energy terms), in document order
};

}  // namespace structmd
