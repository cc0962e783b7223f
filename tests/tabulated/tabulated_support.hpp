#pragma once
// Scenes for the tabulated-potential tests: input documents made from positions and force-field
// entries, LAMMPS-format table files written from analytic potentials, and finite differences of the
// energy through the C API.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "physics_support.hpp"

namespace structmd_tabulated {

using structmd_physics::SimHandle;
using Json = nlohmann::json;

// U(x) and -dU/dx.
struct Sample {
    double energy, force;
};
using Potential = std::function<Sample(double)>;

inline Sample lennard_jones(double r) {
    const double s6 = std::pow(r, -6);
    return {4 * (s6 * s6 - s6), 24 * (2 * s6 * s6 - s6) / r};
}
inline Sample harmonic_bond(double r) { return {25 * (r - 1) * (r - 1), -50 * (r - 1)}; }
inline Sample harmonic_angle(double theta) {
    const double d = theta - 1.9;
    return {10 * d * d, -20 * d};
}

// n points of a potential on [lo, hi], evenly spaced.
struct Points {
    std::vector<double> x, energy, force;
};
inline Points sample(const Potential& u, double lo, double hi, int n) {
    Points p;
    for (int i = 0; i < n; ++i) {
        const double x = lo + (hi - lo) * i / (n - 1);
        const Sample s = u(x);
        p.x.push_back(x);
        p.energy.push_back(s.energy);
        p.force.push_back(s.force);
    }
    return p;
}

// Writes a one-section LAMMPS table file; `xScale` converts the abscissa (1/degree for angles, the
// force scaled to match).
inline std::string write_table_file(const std::string& name, const std::string& keyword, const Points& p,
                                    double xScale = 1.0, const std::string& extra = "") {
    const std::string path = std::string(STRUCTMD_TEST_TMP_DIR) + "/" + name;
    std::ofstream out(path);
    out << "# written by the structmd tests\n\n" << keyword << "\nN " << p.x.size() << extra << "\n\n";
    char line[160];
    for (size_t i = 0; i < p.x.size(); ++i) {
        std::snprintf(line, sizeof line, "%zu %.17g %.17g %.17g\n", i + 1, p.x[i] * xScale, p.energy[i],
                      p.force[i] / xScale);
        out << line;
    }
    return path;
}

inline Json document(double box, const std::vector<structmd_physics::Vec3>& positions,
                     const std::vector<std::string>& types, const Json& forcefield) {
    Json typeRows = Json::array();
    std::vector<std::string> names;
    for (const std::string& t : types)
        if (std::find(names.begin(), names.end(), t) == names.end()) names.push_back(t);
    for (const std::string& t : names) typeRows.push_back({t, 1.0, 0.5, 0.0});
    Json state = Json::array(), structure = Json::array();
    for (size_t i = 0; i < positions.size(); ++i) {
        state.push_back({i, {positions[i][0], positions[i][1], positions[i][2]}});
        structure.push_back({i, types[i]});
    }
    return {{"system", {{"info", {{"type", {"Simulation", "Information"}}, {"parameters", {{"name", "t"}, {"seed", 1}}}}}}},
            {"global",
             {{"units", {{"type", {"Units", "None"}}}},
              {"types", {{"type", {"Types", "Basic"}}, {"labels", {"name", "mass", "radius", "charge"}}, {"data", typeRows}}},
              {"ensemble", {{"type", {"Ensemble", "NVT"}}, {"labels", {"box", "temperature"}}, {"data", {{{box, box, box}, 1.0}}}}}}},
            {"integrator",
             {{"vv", {{"type", {"Verlet", "VelocityVerlet"}}, {"parameters", {{"timeStep", 0.001}}}}},
              {"schedule", {{"type", {"Schedule", "Integrator"}}, {"labels", {"order", "integrator", "steps"}}, {"data", {{1, "vv", 1000}}}}}}},
            {"state", {{"labels", {"id", "position"}}, {"data", state}}},
            {"topology", {{"structure", {{"labels", {"id", "type"}}, {"data", structure}}}, {"forceField", forcefield}}}};
}

inline Json neighbour_list() {
    return {{"type", {"VerletConditionalListSet", "all"}}, {"parameters", {{"cutOffVerletFactor", 1.1}}}};
}

// A handle on the CPU (or `backend`) with the document loaded; the status of the load in `status`.
inline SimHandle load(const Json& doc, int* status = nullptr, const std::string& backend = "cpu") {
    structmd_sim* raw = nullptr;
    if (structmd_create(structmd_physics::create_options(backend, "double").c_str(), &raw) != STRUCTMD_OK) return SimHandle();
    SimHandle sim(raw);
    const int s = structmd_load_string(raw, doc.dump().c_str());
    if (status) *status = s;
    return sim;
}

inline std::vector<double> forces(structmd_sim* sim, int64_t n) {
    std::vector<double> f(3 * n);
    if (structmd_get_forces(sim, f.data(), n) != STRUCTMD_OK) return {};
    return f;
}

inline double potential(structmd_sim* sim) {
    double e = NAN;
    structmd_get_energy(sim, "potential", &e);
    return e;
}

// max |F_fd - F| / max |F| with F_fd = -(U(x + h) - U(x - h)) / 2h for every coordinate.
inline double finite_difference_deviation(structmd_sim* sim, std::vector<double> x, double h = 1e-6) {
    const int64_t n = static_cast<int64_t>(x.size() / 3);
    const std::vector<double> f = forces(sim, n);
    std::vector<double> fd(x.size());
    for (size_t k = 0; k < x.size(); ++k) {
        const double x0 = x[k];
        x[k] = x0 + h;
        structmd_set_positions(sim, x.data(), n);
        const double up = potential(sim);
        x[k] = x0 - h;
        structmd_set_positions(sim, x.data(), n);
        const double down = potential(sim);
        x[k] = x0;
        fd[k] = -(up - down) / (2 * h);
    }
    structmd_set_positions(sim, x.data(), n);
    return structmd_physics::max_relative_deviation(fd, f);
}

// The finite-difference deviation of a scene of particles `x` (all of type A) in a box with `forceField`.
inline double gradient_deviation(double box, const std::vector<structmd_physics::Vec3>& x, const Json& forceField) {
    SimHandle sim = load(document(box, x, std::vector<std::string>(x.size(), "A"), forceField));
    std::vector<double> flat;
    for (const structmd_physics::Vec3& v : x) flat.insert(flat.end(), v.begin(), v.end());
    return finite_difference_deviation(sim.get(), flat);
}

}  // namespace structmd_tabulated
