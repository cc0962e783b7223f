#pragma once
// Helpers shared by the robustness tests: handle options, the inputs they load, and reads of
// positions and energies through the public C API.
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "structmd.h"
#include "structmd.hpp"

namespace structmd::robustness {

// One CPU thread per handle: results are bit for bit reproducible, and ThreadSanitizer sees only
// the threads the tests start (the OpenMP runtime is not instrumented).
inline const char* const kHandleOptions = R"({"backend": "cpu", "threads": 1, "log": "quiet"})";

inline std::string read_text(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot read " + path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

// The valid 4-particle document every bad input is derived from.
inline std::string base_input_text() {
    return read_text(std::string(STRUCTMD_ROBUSTNESS_DIR) + "/bad_inputs/base.json");
}

// A cubic lattice of cells^3 Lennard-Jones particles 1.1 sigma apart (no overlaps), with harmonic
// bonds along x, driven by the named integrator ("vv": velocity Verlet, "bbk": Langevin, whose noise
// comes from seed). Velocities are drawn from the seed too.
inline std::string lattice_input(int cells, uint64_t seed, const std::string& integrator, int64_t steps) {
    using nlohmann::json;
    const double spacing = 1.1;
    const double box = spacing * cells;
    json state = json::array(), structure = json::array(), bonds = json::array();
    int64_t id = 0;
    for (int z = 0; z < cells; ++z)
        for (int y = 0; y < cells; ++y)
            for (int x = 0; x < cells; ++x, ++id) {
                state.push_back({id, {-box / 2 + spacing * x, -box / 2 + spacing * y, -box / 2 + spacing * z}});
                structure.push_back({id, "A"});
                if (x > 0) bonds.push_back({id - 1, id});
            }
    json integratorEntry = integrator == "bbk"
        ? json{{"type", {"Langevin", "BBK"}}, {"parameters", {{"timeStep", 0.002}, {"frictionConstant", 1.0}}}}
        : json{{"type", {"Verlet", "VelocityVerlet"}}, {"parameters", {{"timeStep", 0.002}}}};
    json document = {
        {"system", {{"info", {{"type", {"Simulation", "Information"}}, {"parameters", {{"name", "lattice"}, {"seed", seed}}}}}}},
        {"global",
         {{"types", {{"type", {"Types", "Basic"}}, {"labels", {"name", "mass", "radius", "charge"}}, {"data", {{"A", 1.0, 0.5, 0.0}}}}},
          {"ensemble", {{"type", {"Ensemble", "NVT"}}, {"labels", {"box", "temperature"}}, {"data", {{{box, box, box}, 1.0}}}}}}},
        {"state", {{"labels", {"id", "position"}}, {"data", state}}},
        {"topology",
         {{"structure", {{"labels", {"id", "type"}}, {"data", structure}}},
          {"forceField",
           {{"nl", {{"type", {"VerletConditionalListSet", "all"}}, {"parameters", {{"cutOffVerletFactor", 1.2}}}}},
            {"lj", {{"type", {"NonBonded", "LennardJonesType1"}},
                    {"parameters", {{"cutOffFactor", 2.5}, {"condition", "all"}}},
                    {"labels", {"name_i", "name_j", "epsilon", "sigma"}},
                    {"data", {{"A", "A", 1.0, 1.0}}}}},
            {"bonds", {{"type", {"Bond2", "HarmonicCommon_K_r0"}}, {"parameters", {{"K", 100.0}, {"r0", spacing}}},
                       {"labels", {"id_i", "id_j"}}, {"data", bonds}}}}}}},
        {"integrator",
         {{integrator, integratorEntry},
          {"schedule", {{"type", {"Schedule", "Integrator"}}, {"labels", {"order", "integrator", "steps"}},
                        {"data", {{1, integrator, steps}}}}}}}};
    return document.dump();
}

inline int64_t particle_count(structmd_sim* sim) {
    int64_t n = 0;
    host::check(structmd_get_num_particles(sim, &n), sim, "structmd_get_num_particles");
    return n;
}

inline std::vector<double> positions(structmd_sim* sim) {
    const int64_t n = particle_count(sim);
    std::vector<double> xyz(static_cast<size_t>(3 * n));
    host::check(structmd_get_positions(sim, xyz.data(), n), sim, "structmd_get_positions");
    return xyz;
}

inline double energy(structmd_sim* sim, const char* term) {
    double value = 0.0;
    host::check(structmd_get_energy(sim, term, &value), sim, "structmd_get_energy");
    return value;
}

}  // namespace structmd::robustness
