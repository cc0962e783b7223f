#pragma once
// Scenes for the Expression components' tests, through the C API: a handful of particles in a
// periodic box, each Expression entry beside the built-in term it reproduces, and the evaluation of
// energy (a term or the total) and forces on a given backend and precision.
#include <string>
#include <vector>

#include "../physics/physics_support.hpp"

namespace structmd_expression_test {

using namespace structmd_physics;

inline constexpr double kBox = 8.0;

// 10 particles, none closer than 0.9 to another; particles 0 and 1 straddle the boundary in x
// (minimum image 0.88 apart), and the chain 2-3-4-5 is bent and not planar.
inline const std::vector<Vec3>& positions() {
    static const std::vector<Vec3> p = {
        {-3.7, 0.1, 0.2},  {3.5, 0.3, -0.1}, {0.0, 0.0, 0.0},   {1.1, 0.0, 0.0},  {1.5, 1.0, 0.0},
        {2.6, 1.1, 0.5},   {-1.2, 1.9, -1.3}, {-0.4, -1.6, 1.1}, {1.8, -1.5, -0.9}, {-2.2, -0.3, 1.7}};
    return p;
}
inline const std::vector<std::string>& types() {
    static const std::vector<std::string> t = {"A", "B", "A", "B", "A", "B", "A", "A", "B", "B"};
    return t;
}

inline std::string neighbour_list(const std::string& condition = "all") {
    return "\"nl\": {\"type\": [\"VerletConditionalListSet\", \"" + condition +
           "\"], \"parameters\": {\"cutOffVerletFactor\": 1.2}}";
}

// An LJ type-pair table, one sigma for all (the expression's cutOff is one distance).
inline const char* kLennardJonesData = "[[\"A\", \"A\", 1.0, 1.0], [\"A\", \"B\", 1.3, 1.0], [\"B\", \"B\", 0.7, 1.0]]";

inline std::string builtin_lj(const std::string& name, bool shift, const std::string& extra = "") {
    return "\"" + name + "\": {\"type\": [\"NonBonded\", \"LennardJonesType1\"], \"parameters\": {\"cutOffFactor\": 2.5, "
           "\"condition\": \"all\", \"shift\": " + (shift ? "true" : "false") + extra +
           "}, \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"], \"data\": " + kLennardJonesData + "}";
}

inline std::string expression_lj(const std::string& name, bool shift, const std::string& extra = "") {
    return "\"" + name + "\": {\"type\": [\"NonBonded\", \"Expression\"], \"parameters\": {\"cutOff\": 2.5, "
           "\"energy\": \"4 * epsilon * ((sigma / r)^12 - (sigma / r)^6)\", \"condition\": \"all\", \"shift\": " +
           (shift ? "true" : "false") + extra + "}, \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"], \"data\": " +
           kLennardJonesData + "}";
}

struct Evaluation {
    double energy = 0.0;
    std::vector<double> forces;
    std::string error;  // the load's message when it failed
    structmd_status status = STRUCTMD_OK;
};

inline SimHandle load(const std::string& forceField, const std::string& backend, const std::string& precision,
                      Evaluation& result, const std::vector<Vec3>& at = positions()) {
    structmd_sim* raw = nullptr;
    if (structmd_create(create_options(backend, precision).c_str(), &raw) != STRUCTMD_OK) {
        result.status = STRUCTMD_ERR_INTERNAL;
        result.error = structmd_last_error(nullptr);
        return nullptr;
    }
    SimHandle sim(raw);
    const std::string doc = input_document(kBox, at, types(), {}, forceField, 0.001);
    result.status = structmd_load_string(sim.get(), doc.c_str());
    if (result.status != STRUCTMD_OK) {
        result.error = structmd_last_error(sim.get());
        return nullptr;
    }
    return sim;
}

// Energy of `term` ("potential": all) and the forces.
inline Evaluation evaluate(const std::string& forceField, const std::string& term = "potential",
                           const std::string& precision = "double", const std::string& backend = "cpu",
                           const std::vector<Vec3>& at = positions()) {
    Evaluation result;
    SimHandle sim = load(forceField, backend, precision, result, at);
    if (!sim) return result;
    const int64_t n = static_cast<int64_t>(at.size());
    result.forces.resize(3 * n);
    result.status = structmd_get_forces(sim.get(), result.forces.data(), n);
    if (result.status == STRUCTMD_OK) result.status = structmd_get_energy(sim.get(), term.c_str(), &result.energy);
    if (result.status != STRUCTMD_OK) result.error = structmd_last_error(sim.get());
    return result;
}

}  // namespace structmd_expression_test
