// Helpers shared by the physics tests: an owning handle, status checks that print the engine's
// message, a portable random generator and the deviation measures the tests report.
#ifndef STRUCTMD_TESTS_PHYSICS_SUPPORT_HPP
#define STRUCTMD_TESTS_PHYSICS_SUPPORT_HPP

#include <structmd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace structmd_physics {

struct SimDeleter {
    void operator()(structmd_sim* sim) const { structmd_destroy(sim); }
};
using SimHandle = std::unique_ptr<structmd_sim, SimDeleter>;

// Fails the current test with the engine's message when a call does not return STRUCTMD_OK.
#define ASSERT_STRUCTMD_OK(sim, call)                                                   \
    do {                                                                                \
        const structmd_status status_of_call = (call);                                  \
        ASSERT_EQ(status_of_call, STRUCTMD_OK) << #call << ": " << structmd_last_error(sim); \
    } while (0)

inline std::string create_options(const std::string& backend, const std::string& precision) {
    return "{\"backend\": \"" + backend + "\", \"precision\": \"" + precision + "\", \"log\": \"quiet\"}";
}

// SplitMix64: fully specified, so a configuration is the same with every standard library.
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : m_state(seed) {}

    std::uint64_t next() {
        m_state += 0x9E3779B97F4A7C15ull;
        std::uint64_t z = m_state;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }

    double uniform(double low, double high) {
        return low + (high - low) * static_cast<double>(next() >> 11) * 0x1.0p-53;
    }

    // Box-Muller; one draw per call keeps the sequence simple to reason about.
    double normal() {
        const double u1 = 1.0 - uniform(0.0, 1.0);
        const double u2 = uniform(0.0, 1.0);
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
    }

private:
    std::uint64_t m_state;
};

inline double minimum_image(double d, double box_length) {
    return d - box_length * std::round(d / box_length);
}

inline double max_abs(const std::vector<double>& a) {
    double m = 0.0;
    for (double x : a) m = std::max(m, std::abs(x));
    return m;
}

// max_i |a_i - b_i| / max_i |b_i|: the measure of the brief for forces and per-particle values.
inline double max_relative_deviation(const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
    return m / max_abs(b);
}

inline double relative_deviation(double a, double b) { return std::abs(a - b) / std::abs(b); }

// ||A - B||_F / ||B||_F for 3x3 tensors.
inline double tensor_relative_deviation(const std::array<double, 9>& a, const std::array<double, 9>& b) {
    double diff = 0.0, norm = 0.0;
    for (int k = 0; k < 9; ++k) {
        diff += (a[k] - b[k]) * (a[k] - b[k]);
        norm += b[k] * b[k];
    }
    return std::sqrt(diff / norm);
}

using Vec3 = std::array<double, 3>;

// A jittered simple cubic lattice at density ~0.8, a liquid's neighbourhoods within a few steps:
// side^3 sites in a cubic box of edge side / 0.93 (returned), each moved by up to a tenth of the
// spacing along each axis. site(a, b, c, position) is called for each site in order, after its
// position's draws from rng, so that it may draw more (velocities) in the same sequence.
template <class Site>
double jittered_lattice(int side, SplitMix64& rng, Site&& site) {
    const double spacing = 1.0 / 0.93, box = side * spacing;
    for (int a = 0; a < side; ++a)
        for (int b = 0; b < side; ++b)
            for (int c = 0; c < side; ++c) {
                const Vec3 position{(a + rng.uniform(-0.1, 0.1)) * spacing - 0.5 * box,
                                    (b + rng.uniform(-0.1, 0.1)) * spacing - 0.5 * box,
                                    (c + rng.uniform(-0.1, 0.1)) * spacing - 0.5 * box};
                site(a, b, c, position);
            }
    return box;
}

inline std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

inline std::string vec_text(const Vec3& v) { return "[" + number(v[0]) + ", " + number(v[1]) + ", " + number(v[2]) + "]"; }

// A whole input document (units None and temperature 1 unless given, two types A and B of mass 1,
// cubic periodic box, one VelocityVerlet integrator with a long schedule) around the given forceField
// entries. `units`: global.units' subclass.
inline std::string input_document(double box_length, const std::vector<Vec3>& positions,
                                  const std::vector<std::string>& type_names, const std::vector<Vec3>& velocities,
                                  const std::string& force_field, double time_step, const std::string& units = "None",
                                  double temperature = 1.0) {
    std::string state, structure;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const std::string separator = i == 0 ? "" : ",\n";
        state += separator + "[" + std::to_string(i) + ", " + vec_text(positions[i]) +
                 (velocities.empty() ? "" : ", " + vec_text(velocities[i])) + "]";
        structure += separator + "[" + std::to_string(i) + ", \"" + type_names[i] + "\"]";
    }
    const std::string box = number(box_length);
    return "{\"system\": {\"info\": {\"type\": [\"Simulation\", \"Information\"], \"parameters\": {\"name\": \"physics\"}}},\n"
           "\"global\": {\"units\": {\"type\": [\"Units\", \"" + units + "\"]},\n"
           "  \"types\": {\"type\": [\"Types\", \"Basic\"], \"labels\": [\"name\", \"mass\", \"radius\", \"charge\"],\n"
           "            \"data\": [[\"A\", 1.0, 0.5, 0.0], [\"B\", 1.0, 0.5, 0.0]]},\n"
           "  \"ensemble\": {\"type\": [\"Ensemble\", \"NVT\"], \"labels\": [\"box\", \"temperature\"], \"data\": [[[" +
           box + ", " + box + ", " + box + "], " + number(temperature) + "]]}},\n"
           "\"integrator\": {\"vv\": {\"type\": [\"Verlet\", \"VelocityVerlet\"], \"parameters\": {\"timeStep\": " +
           number(time_step) + "}},\n"
           "  \"schedule\": {\"type\": [\"Schedule\", \"Integrator\"], \"labels\": [\"order\", \"integrator\", \"steps\"],\n"
           "               \"data\": [[1, \"vv\", 1000000]]}},\n"
           "\"state\": {\"labels\": [\"id\", \"position\"" + std::string(velocities.empty() ? "" : ", \"velocity\"") +
           "], \"data\": [\n" + state + "]},\n"
           "\"topology\": {\"structure\": {\"labels\": [\"id\", \"type\"], \"data\": [\n" + structure + "]},\n"
           "  \"forceField\": {\n" + force_field + "}}}\n";
}

// The main() of a test that needs the CUDA backend: GTEST_SKIP would report success to CTest, so a
// missing GPU must read as "skipped" (exit 77, SKIP_RETURN_CODE) instead.
inline int run_tests_if_cuda(int argc, char** argv) {
    structmd_sim* probe = nullptr;
    if (structmd_create(create_options("cuda", "double").c_str(), &probe) != STRUCTMD_OK) {
        std::printf("skipped: no usable CUDA backend: %s\n", structmd_last_error(nullptr));
        return 77;
    }
    structmd_destroy(probe);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}

// The main() of a test run on either backend: `--backend=NAME` sets `backend` (cpu by default), and
// the CUDA run reads as skipped without a GPU.
inline int run_tests_on_backend(int argc, char** argv, std::string& backend) {
    for (int k = 1; k < argc; ++k)
        if (std::strncmp(argv[k], "--backend=", 10) == 0) backend = argv[k] + 10;
    if (backend == "cuda") return run_tests_if_cuda(argc, argv);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}

}  // namespace structmd_physics

#endif
