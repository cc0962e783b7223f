// The GPU's neighbour lists in each of their layouts against the CPU's: a Lennard-Jones liquid's
// forces and energy, CUDA against CPU in the same precision, at sizes where the CUDA backend lays a
// list out by rows (several lanes a particle), by columns of chunks built with several lanes, and by
// columns of chunks with one thread a particle (the last two from about 34,000 and 270,000
// particles on a GPU of 132 multiprocessors; the sizes here clear both on the GPUs we know). One type
// takes the pair kernels of one type (forces alone), the energy and two types the general ones.
// Exits with 77 (skipped for CTest) when no CUDA backend is usable.
#include "physics_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace structmd_physics {
namespace {

// The liquid's LJ pairs: name_i, name_j, epsilon, sigma (r_c = 2.5 sigma, shifted).
struct LjPair {
    const char* a;
    const char* b;
    double epsilon, sigma;
};
std::vector<LjPair> lj_pairs(bool twoTypes) {
    if (!twoTypes) return {{"A", "A", 1.0, 1.0}};
    return {{"A", "A", 1.0, 1.0}, {"A", "B", 1.2, 1.05}, {"B", "B", 0.8, 1.1}};
}

// A jittered lattice liquid (physics_support.hpp), side^3 particles of type A (and B on every third
// site where twoTypes).
std::string liquid(int side, bool twoTypes) {
    SplitMix64 rng(31);
    std::vector<Vec3> positions;
    std::vector<std::string> types;
    const double box = jittered_lattice(side, rng, [&](int a, int b, int c, const Vec3& position) {
        positions.push_back(position);
        types.push_back(twoTypes && (a + b + c) % 3 == 0 ? "B" : "A");
    });
    std::string pairs;
    for (const LjPair& p : lj_pairs(twoTypes))
        pairs += std::string(pairs.empty() ? "" : ", ") + "[\"" + p.a + "\", \"" + p.b + "\", " + number(p.epsilon) + ", " +
                 number(p.sigma) + "]";
    const std::string forceField =
        "\"nl\": {\"type\": [\"VerletConditionalListSet\", \"all\"], \"parameters\": {\"cutOffVerletFactor\": 1.12}},\n"
        "\"lj\": {\"type\": [\"NonBonded\", \"LennardJonesType1\"],\n"
        "       \"parameters\": {\"cutOffFactor\": 2.5, \"condition\": \"all\", \"shift\": true},\n"
        "       \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"], \"data\": [" + pairs + "]}";
    return input_document(box, positions, types, {}, forceField, 0.004);
}

// The largest |F(r_c)| of the liquid's pairs.
double cutoff_force(bool twoTypes) {
    double largest = 0.0;
    for (const LjPair& p : lj_pairs(twoTypes)) {
        const double rc = 2.5 * p.sigma, s6 = std::pow(p.sigma / rc, 6);
        largest = std::max(largest, std::abs(24.0 * p.epsilon * (2.0 * s6 * s6 - s6) / rc));
    }
    return largest;
}

struct Evaluated {
    std::vector<double> forces;
    double energy = 0.0;
};

Evaluated evaluate(const std::string& input, const std::string& backend, const std::string& precision) {
    Evaluated e;
    structmd_sim* raw = nullptr;
    if (structmd_create(create_options(backend, precision).c_str(), &raw) != STRUCTMD_OK) {
        ADD_FAILURE() << backend << "/" << precision << ": " << structmd_last_error(nullptr);
        return e;
    }
    SimHandle sim(raw);
    if (structmd_load_string(sim.get(), input.c_str()) != STRUCTMD_OK) {
        ADD_FAILURE() << backend << "/" << precision << ": " << structmd_last_error(sim.get());
        return e;
    }
    std::int64_t n = 0;
    EXPECT_EQ(structmd_get_num_particles(sim.get(), &n), STRUCTMD_OK);
    e.forces.resize(3 * n);
    // Forces first, alone: the kernels of forces alone; then the energy, through the general ones.
    EXPECT_EQ(structmd_get_forces(sim.get(), e.forces.data(), n), STRUCTMD_OK) << structmd_last_error(sim.get());
    EXPECT_EQ(structmd_get_energy(sim.get(), "potential", &e.energy), STRUCTMD_OK) << structmd_last_error(sim.get());
    return e;
}

void expect_backends_agree(int side, bool twoTypes) {
    const std::string input = liquid(side, twoTypes);
    for (const std::string precision : {"single", "mixed", "double"}) {
        SCOPED_TRACE(std::to_string(side * side * side) + " particles, " + (twoTypes ? "two types, " : "one type, ") +
                     precision);
        const Evaluated cpu = evaluate(input, "cpu", precision), cuda = evaluate(input, "cuda", precision);
        ASSERT_EQ(cpu.forces.size(), cuda.forces.size());
        const double tolerance = precision == "double" ? 1e-10 : 1e-5;
        // A pair whose distance the two backends round to either side of the cutoff adds the force
        // there, |F(r_c)| (LJ's shift moves the energy alone), to its particles on one backend only:
        // a few such pairs are expected among the 17 million of 512,000 particles in float, each
        // 1.5e-4 of the largest force. Such particles are outliers; a list that lost or misread
        // entries would make thousands, or miss pairs well inside the cutoff.
        const double largest = max_abs(cpu.forces), tight = tolerance * largest;
        const double jump = cutoff_force(twoTypes);
        int outliers = 0;
        double worst = 0.0;
        for (std::size_t c = 0; c < cpu.forces.size(); c += 3) {
            double d = 0.0;
            for (int a = 0; a < 3; ++a) d = std::max(d, std::abs(cuda.forces[c + a] - cpu.forces[c + a]));
            worst = std::max(worst, d);
            if (d > tight) {
                ++outliers;
                EXPECT_LT(d, 2.0 * jump + tight) << "particle " << c / 3 << ": more than two pairs at the cutoff";
            }
        }
        const int particles = side * side * side;
        std::printf("[ deviation ] %d particles %s %s: forces %.3e of the largest (%d particles beyond %.0e, "
                    "the cutoff's force %.2e), energy %.3e\n",
                    particles, twoTypes ? "two types" : "one type", precision.c_str(), worst / largest, outliers,
                    tolerance, jump / largest, relative_deviation(cuda.energy, cpu.energy));
        EXPECT_LE(outliers, 4 + particles / 10000);
        EXPECT_LT(relative_deviation(cuda.energy, cpu.energy), tolerance);
    }
}

TEST(ListLayouts, ByRowsSeveralLanesAParticle) { expect_backends_agree(14, false); }

TEST(ListLayouts, ByColumnsOfChunksBuiltWithSeveralLanes) {
    expect_backends_agree(37, false);
    expect_backends_agree(37, true);
}

TEST(ListLayouts, ByColumnsOfChunksOneThreadAParticle) {
    expect_backends_agree(80, false);
    expect_backends_agree(80, true);
}

}  // namespace
}  // namespace structmd_physics

int main(int argc, char** argv) { return structmd_physics::run_tests_if_cuda(argc, argv); }
