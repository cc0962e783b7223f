// Helpers of the stability tests (and of tests/neighbour/test_list_half_skin.cpp): input documents
// built as JSON, loading a handle, reading particle arrays and counters through the C API, lattices,
// and an all-pairs Lennard-Jones reference in double precision with the minimum image.
#ifndef STRUCTMD_TESTS_STABILITY_SUPPORT_HPP
#define STRUCTMD_TESTS_STABILITY_SUPPORT_HPP

#include "physics_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <regex>
#include <string>
#include <vector>

namespace structmd_stability {

using structmd_physics::create_options;
using structmd_physics::minimum_image;
using structmd_physics::SimHandle;
using structmd_physics::SplitMix64;
using structmd_physics::Vec3;
using json = nlohmann::json;

// Everything an input document of these tests varies: one particle type "A", units None (k_B = 1),
// an orthorhombic box, one integrator run for `steps` steps.
struct SystemSpec {
    Vec3 box{10.0, 10.0, 10.0};
    std::vector<Vec3> positions;
    std::vector<Vec3> velocities;  // empty: the engine draws them at `temperature`
    double mass = 1.0;
    double temperature = 1.0;
    json force_field = json::object();
    json integrator;  // one integrator entry, e.g. velocity_verlet(0.005)
    json simulation_step = json::object();
    std::int64_t steps = 1000000;
};

inline json velocity_verlet(double time_step) {
    return {{"type", {"Verlet", "VelocityVerlet"}}, {"parameters", {{"timeStep", time_step}}}};
}

inline json vector_json(const Vec3& v) { return json::array({v[0], v[1], v[2]}); }

inline json input_document(const SystemSpec& spec) {
    json state = json::array(), structure = json::array();
    for (std::size_t i = 0; i < spec.positions.size(); ++i) {
        json row = {i, vector_json(spec.positions[i])};
        if (!spec.velocities.empty()) row.push_back(vector_json(spec.velocities[i]));
        state.push_back(row);
        structure.push_back({i, "A"});
    }
    json state_labels = {"id", "position"};
    if (!spec.velocities.empty()) state_labels.push_back("velocity");
    json document = {
        {"system", {{"info", {{"type", {"Simulation", "Information"}}, {"parameters", {{"name", "stability"}, {"seed", 6}}}}}}},
        {"global",
         {{"units", {{"type", {"Units", "None"}}}},
          {"types",
           {{"type", {"Types", "Basic"}},
            {"labels", {"name", "mass", "radius", "charge"}},
            {"data", {{"A", spec.mass, 0.5, 0.0}}}}},
          {"ensemble",
           {{"type", {"Ensemble", "NVT"}},
            {"labels", {"box", "temperature"}},
            {"data", {{vector_json(spec.box), spec.temperature}}}}}}},
        {"integrator",
         {{"run", spec.integrator},
          {"schedule",
           {{"type", {"Schedule", "Integrator"}},
            {"labels", {"order", "integrator", "steps"}},
            {"data", {{1, "run", spec.steps}}}}}}},
        {"state", {{"labels", state_labels}, {"data", state}}},
        {"topology", {{"structure", {{"labels", {"id", "type"}}, {"data", structure}}}, {"forceField", spec.force_field}}}};
    if (!spec.simulation_step.empty()) document["simulationStep"] = spec.simulation_step;
    return document;
}

// Lennard-Jones type 1 between all pairs through the list "nl", cut at cutoff_factor x sigma.
inline json lennard_jones_force_field(double sigma, double cutoff_factor, double verlet_factor, bool shift) {
    return {{"nl", {{"type", {"VerletConditionalListSet", "all"}}, {"parameters", {{"cutOffVerletFactor", verlet_factor}}}}},
            {"lj",
             {{"type", {"NonBonded", "LennardJonesType1"}},
              {"parameters", {{"cutOffFactor", cutoff_factor}, {"condition", "all"}, {"shift", shift}}},
              {"labels", {"name_i", "name_j", "epsilon", "sigma"}},
              {"data", {{"A", "A", 1.0, sigma}}}}}};
}

// A handle on the given backend and precision holding the document; null (and a test failure with
// the engine's message) when either step fails.
inline SimHandle load_document(const json& document, const std::string& backend = "cpu",
                               const std::string& precision = "double") {
    structmd_sim* raw = nullptr;
    if (structmd_create(create_options(backend, precision).c_str(), &raw) != STRUCTMD_OK) {
        ADD_FAILURE() << "structmd_create(" << backend << ", " << precision << "): " << structmd_last_error(nullptr);
        return nullptr;
    }
    SimHandle sim(raw);
    if (structmd_load_string(sim.get(), document.dump().c_str()) != STRUCTMD_OK) {
        ADD_FAILURE() << "structmd_load_string: " << structmd_last_error(sim.get());
        return nullptr;
    }
    return sim;
}

inline std::int64_t particle_count(structmd_sim* sim) {
    std::int64_t n = 0;
    EXPECT_EQ(structmd_get_num_particles(sim, &n), STRUCTMD_OK) << structmd_last_error(sim);
    return n;
}

// Reads a double[3n] (or double[n] with components = 1) array through one of the getters.
using ArrayGetter = structmd_status (*)(structmd_sim*, double*, std::int64_t);
inline std::vector<double> read_array(structmd_sim* sim, ArrayGetter getter, int components = 3) {
    const std::int64_t n = particle_count(sim);
    std::vector<double> values(components * n);
    EXPECT_EQ(getter(sim, values.data(), n), STRUCTMD_OK) << structmd_last_error(sim);
    return values;
}

inline double read_energy(structmd_sim* sim, const char* term) {
    double value = NAN;
    EXPECT_EQ(structmd_get_energy(sim, term, &value), STRUCTMD_OK) << term << ": " << structmd_last_error(sim);
    return value;
}

inline std::vector<double> read_virial(structmd_sim* sim) {
    std::vector<double> w(9);
    EXPECT_EQ(structmd_get_virial(sim, w.data()), STRUCTMD_OK) << structmd_last_error(sim);
    return w;
}

inline json read_counters(structmd_sim* sim) {
    char text[512];
    EXPECT_EQ(structmd_get_counters(sim, text, sizeof text), STRUCTMD_OK) << structmd_last_error(sim);
    return json::parse(text);
}

inline bool all_finite(const std::vector<double>& values) {
    for (double x : values)
        if (!std::isfinite(x)) return false;
    return true;
}

// n positions drawn uniformly in the box, none closer than min_distance (minimum image) to another.
inline std::vector<Vec3> random_positions(const Vec3& box, std::size_t n, double min_distance, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<Vec3> positions;
    while (positions.size() < n) {
        const Vec3 r{rng.uniform(-0.5, 0.5) * box[0], rng.uniform(-0.5, 0.5) * box[1], rng.uniform(-0.5, 0.5) * box[2]};
        bool clear = true;
        for (const Vec3& q : positions) {
            double r2 = 0.0;
            for (int k = 0; k < 3; ++k) {
                const double d = minimum_image(r[k] - q[k], box[k]);
                r2 += d * d;
            }
            clear = clear && r2 >= min_distance * min_distance;
        }
        if (clear) positions.push_back(r);
    }
    return positions;
}

inline std::vector<double> flatten(const std::vector<Vec3>& vectors) {
    std::vector<double> flat;
    for (const Vec3& v : vectors) flat.insert(flat.end(), v.begin(), v.end());
    return flat;
}

// The number after `word` in an engine message ("step 12, particle id 7: ..."), or -1 if absent.
inline long long number_after(const std::string& message, const std::string& word) {
    std::smatch match;
    if (!std::regex_search(message, match, std::regex(word + "\\s+(\\d+)"))) return -1;
    return std::stoll(match[1].str());
}

// Cubic fcc lattice of 4 cells^3 particles at the given density, centred in its box [-L/2, L/2)^3.
inline std::vector<Vec3> fcc_lattice(int cells, double density, double* box_length) {
    const double lattice = std::cbrt(4.0 / density);
    *box_length = cells * lattice;
    const Vec3 basis[4] = {{0.0, 0.0, 0.0}, {0.5, 0.5, 0.0}, {0.5, 0.0, 0.5}, {0.0, 0.5, 0.5}};
    std::vector<Vec3> positions;
    for (int ix = 0; ix < cells; ++ix)
        for (int iy = 0; iy < cells; ++iy)
            for (int iz = 0; iz < cells; ++iz)
                for (const Vec3& b : basis)
                    positions.push_back({(ix + b[0] + 0.25) * lattice - 0.5 * *box_length,
                                         (iy + b[1] + 0.25) * lattice - 0.5 * *box_length,
                                         (iz + b[2] + 0.25) * lattice - 0.5 * *box_length});
    return positions;
}

// Maxwell-Boltzmann velocities (mass 1) with zero total momentum, scaled to exactly temperature
// for 3N - 3 degrees of freedom.
inline std::vector<Vec3> thermal_velocities(std::size_t n, double temperature, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<Vec3> velocities(n);
    Vec3 mean{0.0, 0.0, 0.0};
    for (Vec3& v : velocities)
        for (int k = 0; k < 3; ++k) {
            v[k] = rng.normal();
            mean[k] += v[k] / n;
        }
    double twice_kinetic = 0.0;
    for (Vec3& v : velocities)
        for (int k = 0; k < 3; ++k) {
            v[k] -= mean[k];
            twice_kinetic += v[k] * v[k];
        }
    const double scale = std::sqrt(temperature * (3.0 * n - 3.0) / twice_kinetic);
    for (Vec3& v : velocities)
        for (double& c : v) c *= scale;
    return velocities;
}

struct PairReference {
    double energy = 0.0;
    std::vector<double> forces;         // double[3n]
    std::vector<double> virial;         // 3x3 row-major, W = sum (r_i - r_j) (x) F_ij
    std::vector<double> energies;       // double[n], half of each pair's energy to each particle
    std::vector<double> force_scale;    // double[n], sum over the particle's pairs of |F_ij|
    std::vector<double> energy_scale;   // double[n], sum over the particle's pairs of |U_ij| / 2
    int pairs_within_cutoff = 0;
};

// Lennard-Jones type 1 (epsilon 1) over every pair within the cutoff, minimum image in an
// orthorhombic box, no neighbour list: the yardstick for the engine's list and forces.
inline PairReference all_pairs_lennard_jones(const std::vector<double>& xyz, const Vec3& box, double sigma,
                                             double cutoff, bool shift) {
    const auto energy_at = [sigma](double r2) {
        const double s6 = std::pow(sigma * sigma / r2, 3);
        return 4.0 * (s6 * s6 - s6);
    };
    const double energy_shift = shift ? energy_at(cutoff * cutoff) : 0.0;
    const std::size_t n = xyz.size() / 3;
    PairReference out;
    out.forces.assign(xyz.size(), 0.0);
    out.virial.assign(9, 0.0);
    out.energies.assign(n, 0.0);
    out.force_scale.assign(n, 0.0);
    out.energy_scale.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            double d[3], r2 = 0.0;  // d = r_j - r_i
            for (int k = 0; k < 3; ++k) {
                d[k] = minimum_image(xyz[3 * j + k] - xyz[3 * i + k], box[k]);
                r2 += d[k] * d[k];
            }
            if (r2 >= cutoff * cutoff) continue;
            ++out.pairs_within_cutoff;
            const double u = energy_at(r2) - energy_shift;
            out.energy += u;
            const double s6 = std::pow(sigma * sigma / r2, 3);
            const double du_dr_over_r = -24.0 * (2.0 * s6 * s6 - s6) / r2;
            for (std::size_t p : {i, j}) {
                out.energies[p] += 0.5 * u;
                out.energy_scale[p] += 0.5 * std::abs(u);
                out.force_scale[p] += std::abs(du_dr_over_r) * std::sqrt(r2);
            }
            for (int k = 0; k < 3; ++k) {
                out.forces[3 * i + k] += du_dr_over_r * d[k];  // F_i = U'(r) d / r
                out.forces[3 * j + k] -= du_dr_over_r * d[k];
            }
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) out.virial[3 * a + b] += -d[a] * du_dr_over_r * d[b];
        }
    return out;
}

// The main of a test program run with --backend=NAME (default `backend`): GTEST_SKIP would report
// success to CTest, so a backend that cannot be had (no GPU) exits 77, which CTest reads as skipped.
inline int run_tests_on_backend(int argc, char** argv, std::string& backend, const std::string& precision) {
    ::testing::InitGoogleTest(&argc, argv);
    for (int k = 1; k < argc; ++k)
        if (std::strncmp(argv[k], "--backend=", 10) == 0) backend = argv[k] + 10;
    structmd_sim* probe = nullptr;
    if (structmd_create(create_options(backend, precision).c_str(), &probe) != STRUCTMD_OK) {
        std::printf("skipped: no usable %s backend: %s\n", backend.c_str(), structmd_last_error(nullptr));
        return 77;
    }
    structmd_destroy(probe);
    return RUN_ALL_TESTS();
}

}  // namespace structmd_stability

#endif
