#pragma once
// Minimal inputs made from a registry entry's schema alone, for the tests that walk the registries.
// Every entry is exercised on one small system: four particles in a bent, non-planar chain (so every
// bond, angle and dihedral is defined and no two particles are closer than 1.08) of types A, B, A, B,
// in a periodic box of 20. Each parameter gets numbers that are distinct from those of every other
// parameter and, in a table, from row to row, so that a value read under the wrong name, or from the
// wrong row, changes the result. A few values no schema can tell are in overrides(), each with why.
#include <array>
#include <cctype>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/parameters.hpp"
#include "core/registry.hpp"
#include "forcefield/component_registry.hpp"
#include "integrators/integrator_spec.hpp"

namespace structmd::registry_test {

// Keys keep the order they were written in, so a test can reorder them on purpose.
using Json = nlohmann::ordered_json;

inline constexpr double kBox = 20.0;
inline constexpr double kCutOffFactor = 2.5;  // pairs: the largest sigma below, 1.16, gives 2.9 < kBox / 2
inline constexpr const char* kEntryName = "underTest";

inline const std::vector<std::array<double, 3>>& chain_positions() {
    static const std::vector<std::array<double, 3>> positions = {
        {0.0, 0.0, 0.0}, {1.1, 0.0, 0.0}, {1.5, 1.0, 0.0}, {2.6, 1.1, 0.5}};
    return positions;
}
inline const std::vector<std::string>& chain_types() {
    static const std::vector<std::string> types = {"A", "B", "A", "B"};
    return types;
}

// The particles' magnetic moments [mx, my, mz, M] (body-frame direction, magnitude), for the magnetic
// terms: each along another direction and of another magnitude, so that every pair of them and any
// field make torques.
inline const std::vector<Json>& chain_magnetizations() {
    static const std::vector<Json> moments = {Json::array({1.0, 0.0, 0.0, 1.0}), Json::array({0.0, 1.0, 0.0, 1.2}),
                                              Json::array({0.0, 0.0, 1.0, 0.8}), Json::array({0.6, 0.0, 0.8, 1.1})};
    return moments;
}

// The types, one row each of a table of types.
inline const std::vector<std::string>& type_names() {
    static const std::vector<std::string> names = {"A", "B"};
    return names;
}

// The unordered type pairs of a pair table, one row each.
inline const std::vector<std::array<const char*, 2>>& type_pairs() {
    static const std::vector<std::array<const char*, 2>> pairs = {{"A", "A"}, {"A", "B"}, {"B", "B"}};
    return pairs;
}

// The bonds of each arity along the chain: two of each where the chain allows, so that per-bond
// values differ from bond to bond.
inline std::vector<std::vector<int>> chain_bonds(int arity) {
    switch (arity) {
        case 1: return {{0}, {3}};
        case 2: return {{0, 1}, {1, 2}, {2, 3}};
        case 3: return {{0, 1, 2}, {1, 2, 3}};
        case 4: return {{0, 1, 2, 3}, {3, 2, 1, 0}};
        default: return {};
    }
}

// The force-field components whose input their schema alone describes, which the walks below load.
// A configurable component (a table, an expression) derives its parameters from its entry, so no
// entry made from a schema loads; each such component has its own suite (tests/tabulated, ...).
inline std::vector<ComponentKey> schema_forcefield_keys() {
    std::vector<ComponentKey> keys;
    for (const ForceFieldComponent& c : forcefield_registry().entries())
        if (!c.configure) keys.push_back(c.key);
    return keys;
}

// Values no schema can tell. Everything not listed here takes generic_numbers().
struct Override {
    ComponentKey key;  // an empty class matches every class
    const char* parameter;
    std::vector<double> numbers;
};

inline const std::vector<Override>& overrides() {
    static const std::vector<Override> table = {
        // The particles (|z| <= 0.5) must lie between the plates, at +-S/2, and minPlatesSeparation <=
        // S <= maxPlatesSeparation, so that the clamp does not hide S at t = 0 (generic values are
        // all about 1, which puts a particle on a plate and min above max).
        {{"External", "Plates"}, "platesSeparation", {8.0}},
        {{"External", "Plates"}, "minPlatesSeparation", {6.0}},
        {{"External", "Plates"}, "maxPlatesSeparation", {12.0}},
        // Likewise the shell: centred on the chain (every particle within 1.7 of the centre), well
        // away from every particle, with minShellRadius <= shellRadius <= maxShellRadius.
        {{"External", "SphericalShell"}, "shellCenter", {1.3, 0.5, 0.125}},
        {{"External", "SphericalShell"}, "shellRadius", {6.0}},
        {{"External", "SphericalShell"}, "minShellRadius", {4.0}},
        {{"External", "SphericalShell"}, "maxShellRadius", {9.0}},
        // The plain cylinder's solid must leave the chain outside it, and near enough to act on it:
        // the plane below the chain, and a well of radius 2 whose rim is within 2^(1/6) sigma of
        // particles 1 and 2 (generic values put every particle inside the solid, where it feels
        // nothing). Not -1, which the changes of registry.order leave where it is.
        {{"Surface", "WCA_PlainCylinder"}, "plainPosition", {-0.8}},
        {{"Surface", "WCA_PlainCylinder"}, "cylinderRadius", {2.0}},
        // Its validate() accepts only 0 (removing the centre-of-mass motion is not supported); the
        // schema says only "an integer".
        {{"Langevin", "BBK"}, "stopTransRotSteps", {0.0}},
        // The minimiser's first step moves the particle of the largest force by h: about 1 overshoots
        // every spring's minimum, each move is undone, and nothing ever moves. Under each of its names
        // (an empty class matches any).
        {{"", "SteepestDescent"}, "h", {0.01}},
        // Their validate() takes a tolerance in [1e-10, 0.1]; generic values are about 1. Under both of
        // their class names.
        {{"", "ForceCouplingMethod"}, "tolerance", {1e-3}},
        {{"", "PositivelySplitEwald"}, "tolerance", {1e-3}},
        // Likewise the planar hydrodynamics' validate().
        {{"BDHIDoublyPeriodic", "Quasi2D"}, "tolerance", {1e-3}},
        // The slab's grid must fit the periodic box of kBox (20) and resolve the Gaussian (spacing
        // below 2 a/sqrt(pi)), its slab fit in the box's z, its kernels' alpha stay within w/2, its
        // nz be left to the spacing (0) and its Lanczos tolerance be at most 0.1.
        {{"BDHIDoublyPeriodic", "DPStokes"}, "nx", {32.0}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "ny", {32.0}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "nz", {0.0}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "Lx", {kBox}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "Ly", {kBox}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "H", {12.0}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "w", {6.0}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "alpha", {3.0}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "w_d", {6.0}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "alpha_d", {3.0}},
        {{"BDHIDoublyPeriodic", "DPStokes"}, "tolerance", {1e-3}},
        // The inertial coupling methods' cells: whole numbers, at least 4, given all three or none.
        {{"FluctuatingHydrodynamics", "IncompressibleInertialCoupling"}, "cellDimX", {8.0}},
        {{"FluctuatingHydrodynamics", "IncompressibleInertialCoupling"}, "cellDimY", {10.0}},
        {{"FluctuatingHydrodynamics", "IncompressibleInertialCoupling"}, "cellDimZ", {12.0}},
        {{"FluctuatingHydrodynamics", "CompressibleInertialCoupling"}, "cellDimX", {8.0}},
        {{"FluctuatingHydrodynamics", "CompressibleInertialCoupling"}, "cellDimY", {10.0}},
        {{"FluctuatingHydrodynamics", "CompressibleInertialCoupling"}, "cellDimZ", {12.0}},
        // zeroEnergy acts only in the rows whose epsilon is 0 (the excluded-volume form); generic
        // epsilons are all about 1.
        {{"NonBonded", "KimHummer"}, "epsilon", {0.0}},
        // The WCA core of MorseWCA acts only closer than r0: generic r0 (about 1) leaves the chain's
        // bonds outside it, where eps0 changes nothing.
        {{"Bond2", "MorseWCACommon_eps0"}, "r0", {2.0}},
    };
    return table;
}

// The numbers of the k-th parameter of a schema in the row-th row of a table (row 0 for values given
// once): within the parameter's rule, different for every (k, row), and each about 1, so that lengths
// sit near the bond lengths of the chain and every energy stays finite.
inline std::vector<double> generic_numbers(const Parameter& p, size_t k, int row) {
    std::vector<double> numbers;
    for (int j = 0; j < p.size; ++j) {
        switch (p.must) {
            case Must::be_boolean: numbers.push_back(static_cast<double>((k + row + j) % 2)); break;
            case Must::be_integer:
            case Must::be_positive_integer:
            case Must::be_at_least_one: numbers.push_back(static_cast<double>(1 + k + row + j)); break;
            default: numbers.push_back(1.0 + 0.1 * k + 0.03 * row + 0.01 * j); break;
        }
    }
    return numbers;
}

inline std::vector<double> numbers_for(const ComponentKey& key, const Parameter& p, size_t k, int row) {
    for (const Override& o : overrides())
        if ((o.key.cls.empty() || o.key.cls == key.cls) && o.key.subclass == key.subclass &&
            std::string(o.parameter) == p.name)
            return o.numbers;
    return generic_numbers(p, k, row);
}

// A parameter's numbers as the input writes them: true/false, a number, or a list.
inline Json json_of(const Parameter& p, const std::vector<double>& numbers) {
    if (p.must == Must::be_boolean) return numbers.at(0) != 0.0;
    if (p.size == 1) return numbers.at(0);
    Json list = Json::array();
    for (double x : numbers) list.push_back(x);
    return list;
}

// The numbers of a JSON value as the reader stores them (true is 1, false 0).
inline std::vector<double> numbers_of(const Json& value) {
    if (value.is_boolean()) return {value.get<bool>() ? 1.0 : 0.0};
    if (value.is_number()) return {value.get<double>()};
    std::vector<double> numbers;
    for (const Json& x : value) numbers.push_back(x.get<double>());
    return numbers;
}

inline bool is_common(const ForceFieldComponent& c, const Parameter& p) {
    for (const std::string& name : c.common)
        if (name == p.name) return true;
    return false;
}

// The topology.forceField entry of a component, from its schema.
inline Json forcefield_entry(const ForceFieldComponent& c) {
    Json entry = Json::object();
    entry["type"] = Json::array({c.key.cls, c.key.subclass});
    Json parameters = Json::object();
    switch (c.kind) {
        case InteractionKind::pair: {
            parameters["condition"] = "all";
            if (c.readsCutOffFactor) parameters["cutOffFactor"] = kCutOffFactor;
            // Entry parameters are numbered after the table's, so no two parameters share a number.
            for (size_t k = 0; k < c.entryParameters.size(); ++k) {
                const Parameter& p = c.entryParameters[k];
                parameters[p.name] = json_of(p, numbers_for(c.key, p, c.parameters.size() + k, 0));
            }
            if (!c.parameters.empty()) {
                Json labels = Json::array({"name_i", "name_j"});
                for (const Parameter& p : c.parameters) labels.push_back(p.name);
                Json data = Json::array();
                for (size_t row = 0; row < type_pairs().size(); ++row) {
                    Json line = Json::array({type_pairs()[row][0], type_pairs()[row][1]});
                    for (size_t k = 0; k < c.parameters.size(); ++k)
                        line.push_back(json_of(c.parameters[k], numbers_for(c.key, c.parameters[k], k, int(row))));
                    data.push_back(line);
                }
                entry["labels"] = labels;
                entry["data"] = data;
            }
            break;
        }
        case InteractionKind::bond: {
            static const char* const ids[] = {"id_i", "id_j", "id_k", "id_l"};
            Json labels = Json::array();
            for (int m = 0; m < c.arity; ++m) labels.push_back(ids[m]);
            for (size_t k = 0; k < c.parameters.size(); ++k) {
                const Parameter& p = c.parameters[k];
                if (is_common(c, p))
                    parameters[p.name] = json_of(p, numbers_for(c.key, p, k, 0));
                else
                    labels.push_back(p.name);
            }
            Json data = Json::array();
            const std::vector<std::vector<int>> bonds = chain_bonds(c.arity);
            for (size_t b = 0; b < bonds.size(); ++b) {
                Json line = Json::array();
                for (int id : bonds[b]) line.push_back(id);
                for (size_t k = 0; k < c.parameters.size(); ++k)
                    if (!is_common(c, c.parameters[k]))
                        line.push_back(json_of(c.parameters[k], numbers_for(c.key, c.parameters[k], k, int(b))));
                data.push_back(line);
            }
            entry["labels"] = labels;
            entry["data"] = data;
            break;
        }
        case InteractionKind::external:
            for (size_t k = 0; k < c.parameters.size(); ++k)
                parameters[c.parameters[k].name] = json_of(c.parameters[k], numbers_for(c.key, c.parameters[k], k, 0));
            // A table of types (the Surface family): one row per type, numbered after the entry's own.
            if (!c.typeParameters.empty()) {
                Json labels = Json::array({"name"});
                for (const Parameter& p : c.typeParameters) labels.push_back(p.name);
                Json data = Json::array();
                for (size_t row = 0; row < type_names().size(); ++row) {
                    Json line = Json::array({type_names()[row]});
                    for (size_t k = 0; k < c.typeParameters.size(); ++k)
                        line.push_back(json_of(c.typeParameters[k], numbers_for(c.key, c.typeParameters[k],
                                                                                c.parameters.size() + k, int(row))));
                    data.push_back(line);
                }
                entry["labels"] = labels;
                entry["data"] = data;
            }
            break;
    }
    if (!parameters.empty()) entry["parameters"] = parameters;
    return entry;
}

// An integrator entry, from its schema; the time step is every integrator's (the minimiser accepts it).
inline Json integrator_entry(const IntegratorComponent& c) {
    Json parameters = Json::object();
    parameters["timeStep"] = 0.001;
    for (size_t k = 0; k < c.parameters.size(); ++k)
        parameters[c.parameters[k].name] = json_of(c.parameters[k], numbers_for(c.key, c.parameters[k], k, 0));
    // A named choice takes its last supported name (the magnetic integrators: the full Heun scheme).
    for (const TextOption& option : c.textOptions) parameters[option.name] = option.supported.back();
    return Json{{"type", Json::array({c.key.cls, c.key.subclass})}, {"parameters", parameters}};
}

// The whole document: the chain, its types (distinct charges, for terms of charges; radius 0.5, for
// integrators of mobilities), its magnetic moments, one integrator and the given force field.
inline Json document(const Json& forceField, const Json& integrator = Json()) {
    const Json stepper =
        integrator.is_null() ? Json{{"type", {"Verlet", "VelocityVerlet"}}, {"parameters", {{"timeStep", 0.001}}}}
                             : integrator;
    Json state = Json::array(), structure = Json::array();
    for (size_t i = 0; i < chain_positions().size(); ++i) {
        const auto& r = chain_positions()[i];
        state.push_back(Json::array({i, Json::array({r[0], r[1], r[2]}), Json::array({0.0, 0.0, 0.0}),
                                     chain_magnetizations()[i]}));
        structure.push_back(Json::array({i, chain_types()[i]}));
    }
    Json doc;
    doc["system"] = {{"info", {{"type", {"Simulation", "Information"}}, {"parameters", {{"name", "registry"}}}}}};
    doc["global"] = {
        {"types",
         {{"type", {"Types", "Basic"}},
          {"labels", {"name", "mass", "radius", "charge"}},
          {"data", Json::array({Json::array({"A", 1.0, 0.5, 1.0}), Json::array({"B", 2.0, 0.5, -0.5})})}}},
        // lambda below 1, so that every parameter of a term of lambda (the soft core's alpha, the power
        // n) acts on the result.
        {"ensemble",
         {{"type", {"Ensemble", "NVTlambda"}},
          {"labels", {"box", "temperature", "lambda"}},
          {"data", Json::array({Json::array({Json::array({kBox, kBox, kBox}), 1.0, 0.7})})}}}};
    doc["integrator"] = {{"stepper", stepper},
                         {"schedule",
                          {{"type", {"Schedule", "Integrator"}},
                           {"labels", {"order", "integrator", "steps"}},
                           {"data", Json::array({Json::array({1, "stepper", 10})})}}}};
    doc["state"] = {{"labels", {"id", "position", "velocity", "magnetization"}}, {"data", state}};
    doc["topology"] = {{"structure", {{"labels", {"id", "type"}}, {"data", structure}}}, {"forceField", forceField}};
    return doc;
}

// The document with one component's entry under kEntryName (and the neighbour list a pair term needs,
// and the units a component defined in one unit system needs). A term of no cutoff (Coulomb, Gravity)
// gets an ["NBody", "all"] entry and a box open along every axis, which it needs.
inline Json document_with(const ForceFieldComponent& c, const Json& entry) {
    Json forceField = Json::object();
    if (c.kind == InteractionKind::pair && c.infiniteRange)
        forceField["nl"] = {{"type", {"NBody", "all"}}};
    else if (c.kind == InteractionKind::pair)
        forceField["nl"] = {{"type", {"VerletConditionalListSet", "all"}}, {"parameters", {{"cutOffVerletFactor", 1.2}}}};
    forceField[kEntryName] = entry;
    Json doc = document(forceField);
    if (c.infiniteRange) doc["global"]["ensemble"]["data"][0][0] = {"inf", "inf", "inf"};
    if (!c.units.empty()) doc["global"]["units"] = {{"type", {"Units", c.units}}};
    return doc;
}

inline Json document_with(const ForceFieldComponent& c) { return document_with(c, forcefield_entry(c)); }

// gtest parameter names: the key's two words, letters, digits and underscores only.
inline std::string test_name(const ComponentKey& key) {
    std::string name = key.cls + "_" + key.subclass;
    for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_') ch = '_';
    return name;
}

}  // namespace structmd::registry_test

namespace structmd {
// How gtest prints a test parameter (found by argument-dependent lookup): the key as the input writes it.
inline void PrintTo(const ComponentKey& key, std::ostream* out) { *out << key.text(); }
}  // namespace structmd
