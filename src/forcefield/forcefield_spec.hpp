#pragma once
// The force field as read from topology.forceField: plain data, validated against the system, with
// the JSON path of each entry kept for later messages. Each interaction names its component by key
// and holds its parameters by name; the engine's factories (make_interactors.hpp) turn it into
// interactors.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/box.hpp"
#include "core/error.hpp"
#include "core/parameters.hpp"
#include "core/registry.hpp"
#include "neighbour/pair_filter.hpp"
#include "neighbour/pair_filter_inputs.hpp"

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

// The one rule between pair terms and the box: minimum images are exact only for interactions
// shorter than half the shortest box length. A box open along every axis has no images: any cutoff,
// infinity too (an all-pairs term of no finite range), fits.
inline bool cutoff_fits_box(double cutoff, const std::array<double, 3>& box) {
    const double half = half_shortest_edge(box[0], box[1], box[2]);
    return cutoff < half || is_open_axis(half);
}

// What a configurable component (an expression, a table) derives from its entry when it is read,
// for its engine factory: a compiled expression, a table's coefficients. Each such component
// defines its own derived type.
struct ComponentConfig {
    virtual ~ComponentConfig() = default;
};

// What every interaction entry shares: its name, where it was read, which component it is, when it
// is active (startStep <= step < endStep) and which particles it acts on.
struct InteractionSpec {
    std::string name;
    std::string path;
    ComponentKey key;
    int64_t startStep = 0;
    int64_t endStep = std::numeric_limits<int64_t>::max();
    int group = -1;  // index into ForceFieldSpec::groups; -1: all particles
    std::shared_ptr<const ComponentConfig> config;  // set by configurable components only
};

struct NeighbourListSpec {
    std::string name;
    std::string path;
    ComponentKey key;  // ["VerletConditionalListSet", condition] or ["NBody", "all"]
    bool allPairs = false;  // ["NBody", ...]: the pair terms on it visit every pair, no list is built
    double verletFactor = 1.1;
    double minimumCutoff = 0.0;  // the entry's cutOff parameter
    PairFilterInputs filterInputs;  // exclusions, types or type groups, charges: what its conditions read
};

struct PairSpec : InteractionSpec {
    struct Row {
        int typeI, typeJ;
        ParameterValues values;  // the component's per-type-pair parameters
        int batch = -1;          // the batch (numbered as ForceFieldContext's) of a batched table; -1: all
    };
    int list = 0;  // index into ForceFieldSpec::lists
    PairCondition condition = PairCondition::all;
    double cutOffFactor = 0.0;
    bool shift = false;
    ParameterValues shared;  // the component's parameters given once for every type pair
    std::vector<Row> rows;   // each unordered type pair at most once; none for a term of every type pair
    bool everyTypePair = false;  // the component has no per-type-pair parameters
    bool unlistedPairsInteract = false;  // type pairs the table does not list interact (DLVO's electrostatics)
    double cutoff = 0.0;     // the largest distance at which the term acts, from its functor

    // A batchId column gives each batch its own rows (and its own table).
    bool batched() const { return !rows.empty() && rows.front().batch >= 0; }

    // What the functor is given for one type pair: the shared parameters and the row's.
    ParameterValues values_of(const Row& row) const {
        ParameterValues values = shared;
        for (const auto& [name, numbers] : row.values.all()) values.set(name, numbers);
        return values;
    }
};

struct BondSpec : InteractionSpec {
    int arity = 2;
    std::vector<Parameter> schema;  // the component's parameters, in the layout of `values`
    std::vector<int> members;       // arity particle ids per bond
    std::vector<double> values;     // width_of(schema) numbers per bond, in the schema's order
};

struct ExternalSpec : InteractionSpec {
    struct Row {
        int type;
        int batch = -1;          // the batch (numbered as ForceFieldContext's) of a batched table; -1: all
        ParameterValues values;  // the component's per-type parameters
    };
    ParameterValues values;  // the entry's "parameters"
    bool perType = false;    // the component has per-type parameters (a table of types)
    std::vector<Row> rows;   // perType: each listed type once, or each (batch, type) of a batched table

    // What the functor is given for one type: the entry's parameters and the row's.
    ParameterValues values_of(const Row& row) const {
        ParameterValues merged = values;
        for (const auto& [name, numbers] : row.values.all()) merged.set(name, numbers);
        return merged;
    }
};

struct ForceFieldSpec {
    std::vector<GroupSpec> groups;
    std::vector<NeighbourListSpec> lists;
    std::vector<PairSpec> pairs;
    std::vector<BondSpec> bonds;
    std::vector<ExternalSpec> externals;
    std::vector<std::string> entryNames;  // every interaction entry (energy terms), in document order
    bool clusterPairs = false;  // pair terms may walk cluster pairs (engine option "pair_traversal")

    // The longest distance at which any pair term acts (0 without pair terms).
    double largest_cutoff() const {
        double largest = 0.0;
        for (const PairSpec& pair : pairs) largest = std::max(largest, pair.cutoff);
        return largest;
    }
};

}  // namespace structmd
