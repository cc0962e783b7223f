// The engine option "pair_traversal": an LJ liquid of two types run over cluster pairs and over
// per-particle lists gives the same forces, energy and virial at load, and the same trajectory over
// 300 velocity Verlet steps with several list rebuilds, in double precision. Also that lists the
// cluster kernels do not handle (a condition) and a box too narrow for clusters still run.
// Usage: test_pair_traversal [--backend=cpu|cuda]; with cuda it exits 77 (skipped) without a GPU.
#include "physics_support.hpp"

#include <array>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace structmd_physics {
namespace {

std::string g_backend = "cpu";

// A jittered lattice liquid (physics_support.hpp) with velocities at T ~ 1.5, two types.
std::string liquid(int side, const std::string& list, const std::string& condition) {
    SplitMix64 rng(2024);
    std::vector<Vec3> positions, velocities;
    std::vector<std::string> types;
    const double box = jittered_lattice(side, rng, [&](int a, int b, int c, const Vec3& position) {
        positions.push_back(position);
        velocities.push_back({1.2 * rng.normal(), 1.2 * rng.normal(), 1.2 * rng.normal()});
        types.push_back((a + b + c) % 3 == 0 ? "B" : "A");
    });
    const std::string forceField =
        "\"nl\": {\"type\": [\"VerletConditionalListSet\", \"" + list + "\"], \"parameters\": {\"cutOffVerletFactor\": 1.12}},\n"
        "\"lj\": {\"type\": [\"NonBonded\", \"LennardJonesType1\"],\n"
        "       \"parameters\": {\"cutOffFactor\": 2.5, \"condition\": \"" + condition + "\", \"shift\": true},\n"
        "       \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"],\n"
        "       \"data\": [[\"A\", \"A\", 1.0, 1.0], [\"A\", \"B\", 1.2, 1.05], [\"B\", \"B\", 0.8, 1.1]]}";
    return input_document(box, positions, types, velocities, forceField, 0.004);
}

SimHandle load(const std::string& input, const std::string& traversal) {
    const std::string options = "{\"backend\": \"" + g_backend +
                                "\", \"precision\": \"double\", \"log\": \"quiet\", \"pair_traversal\": \"" + traversal + "\"}";
    structmd_sim* raw = nullptr;
    if (structmd_create(options.c_str(), &raw) != STRUCTMD_OK) {
        ADD_FAILURE() << traversal << ": " << structmd_last_error(nullptr);
        return nullptr;
    }
    SimHandle sim(raw);
    if (structmd_load_string(sim.get(), input.c_str()) != STRUCTMD_OK) {
        ADD_FAILURE() << traversal << ": " << structmd_last_error(sim.get());
        return nullptr;
    }
    return sim;
}

struct Observed {
    std::vector<double> forces, positions;
    double energy = 0.0;
    std::array<double, 9> virial{};
};

Observed observe(structmd_sim* sim) {
    Observed o;
    std::int64_t n = 0;
    EXPECT_EQ(structmd_get_num_particles(sim, &n), STRUCTMD_OK);
    o.forces.resize(3 * n);
    o.positions.resize(3 * n);
    EXPECT_EQ(structmd_get_forces(sim, o.forces.data(), n), STRUCTMD_OK) << structmd_last_error(sim);
    EXPECT_EQ(structmd_get_positions(sim, o.positions.data(), n), STRUCTMD_OK) << structmd_last_error(sim);
    EXPECT_EQ(structmd_get_energy(sim, "potential", &o.energy), STRUCTMD_OK) << structmd_last_error(sim);
    EXPECT_EQ(structmd_get_virial(sim, o.virial.data()), STRUCTMD_OK) << structmd_last_error(sim);
    return o;
}

void expect_same(const Observed& clusters, const Observed& particles, double tolerance, const char* when) {
    EXPECT_LT(max_relative_deviation(clusters.forces, particles.forces), tolerance) << when << ": forces";
    EXPECT_LT(max_relative_deviation(clusters.positions, particles.positions), tolerance) << when << ": positions";
    EXPECT_LT(relative_deviation(clusters.energy, particles.energy), tolerance) << when << ": energy";
    EXPECT_LT(tensor_relative_deviation(clusters.virial, particles.virial), tolerance) << when << ": virial";
}

TEST(PairTraversal, ClustersAndPerParticleListsAgree) {
    const std::string input = liquid(14, "all", "all");  // 2,744 particles, box 15.05: 5 cells a side
    SimHandle clusters = load(input, "clusters"), particles = load(input, "particles");
    ASSERT_TRUE(clusters && particles);
    expect_same(observe(clusters.get()), observe(particles.get()), 1e-12, "at load");
    ASSERT_STRUCTMD_OK(clusters.get(), structmd_step(clusters.get(), 300));
    ASSERT_STRUCTMD_OK(particles.get(), structmd_step(particles.get(), 300));
    // Summation orders differ, so rounding differs by ~1e-16 and grows along the trajectory.
    expect_same(observe(clusters.get()), observe(particles.get()), 1e-8, "after 300 steps");
}

TEST(PairTraversal, ListsTheClustersDoNotHandleStillRun) {
    // A condition (intra: every particle is in model 0, so it holds every pair) and a box of three
    // cells a side.
    for (const std::string& input : {liquid(14, "intra_inter", "intra"), liquid(8, "all", "all")}) {
        SimHandle clusters = load(input, "clusters"), particles = load(input, "particles");
        ASSERT_TRUE(clusters && particles);
        ASSERT_STRUCTMD_OK(clusters.get(), structmd_step(clusters.get(), 20));
        ASSERT_STRUCTMD_OK(particles.get(), structmd_step(particles.get(), 20));
        expect_same(observe(clusters.get()), observe(particles.get()), 1e-12, "after 20 steps");
    }
}

TEST(PairTraversal, UnknownValueIsRefusedByName) {
    structmd_sim* raw = nullptr;
    EXPECT_EQ(structmd_create("{\"pair_traversal\": \"tiles\"}", &raw), STRUCTMD_ERR_ARGUMENT);
    EXPECT_NE(std::strstr(structmd_last_error(nullptr), "pair_traversal"), nullptr) << structmd_last_error(nullptr);
}

}  // namespace
}  // namespace structmd_physics

int main(int argc, char** argv) { return structmd_physics::run_tests_on_backend(argc, argv, structmd_physics::g_backend); }
