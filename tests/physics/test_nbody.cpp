// Pair terms over all pairs (an ["NBody", "all"] list) and open box axes (a length of 0 or "inf"),
// through the C API: unscreened Coulomb among random charges in an open box against a direct sum
// written here (energy, forces, virial) and against finite differences of the energy; a softened
// gravitational cluster whose NVE run keeps its energy and momentum; a Debye-Hueckel term over all
// pairs of a periodic box against the same term over a Verlet list; Verlet lists over open axes against
// all pairs, with clumps far apart along an open axis sharing the repeating cells; batches kept apart;
// checkpoints and structmd_set_box of an open box; and the inputs refused, each naming its path.
// Usage: test_nbody [--backend=cpu|cuda]; with cuda it exits 77 (skipped) without a GPU.
#include "physics_support.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace structmd_physics {
namespace {

std::string g_backend = "cpu";

struct Body {
    Vec3 position;
    Vec3 velocity;
    double mass;
    double charge;
    int batch;
};

// An input of the given bodies (types A and B, units None, temperature 1) with per-particle mass,
// charge and batch columns, the box given as its three JSON cells and one velocity Verlet integrator.
std::string document(const std::vector<Body>& bodies, const std::string& boxCells, const std::string& forceField,
                     double timeStep = 1e-3) {
    std::string state, structure;
    for (size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        const std::string separator = i == 0 ? "" : ",\n";
        state += separator + "[" + std::to_string(i) + ", " + vec_text(b.position) + ", " + vec_text(b.velocity) +
                 ", " + number(b.mass) + ", " + number(b.charge) + "]";
        structure += separator + "[" + std::to_string(i) + ", \"" + (i % 2 ? "B" : "A") + "\", " +
                     std::to_string(b.batch) + "]";
    }
    return "{\"system\": {\"info\": {\"type\": [\"Simulation\", \"Information\"], \"parameters\": {\"name\": \"nbody\"}}},\n"
           "\"global\": {\"units\": {\"type\": [\"Units\", \"None\"]},\n"
           "  \"types\": {\"type\": [\"Types\", \"Basic\"], \"labels\": [\"name\", \"mass\", \"radius\", \"charge\"],\n"
           "            \"data\": [[\"A\", 1.0, 0.5, 0.0], [\"B\", 1.0, 0.5, 0.0]]},\n"
           "  \"ensemble\": {\"type\": [\"Ensemble\", \"NVT\"], \"labels\": [\"box\", \"temperature\"], \"data\": [[[" +
           boxCells + "], 1.0]]}},\n"
           "\"integrator\": {\"vv\": {\"type\": [\"Verlet\", \"VelocityVerlet\"], \"parameters\": {\"timeStep\": " +
           number(timeStep) + "}},\n"
           "  \"schedule\": {\"type\": [\"Schedule\", \"Integrator\"], \"labels\": [\"order\", \"integrator\", \"steps\"],\n"
           "               \"data\": [[1, \"vv\", 1000000]]}},\n"
           "\"state\": {\"labels\": [\"id\", \"position\", \"velocity\", \"mass\", \"charge\"], \"data\": [\n" + state +
           "]},\n"
           "\"topology\": {\"structure\": {\"labels\": [\"id\", \"type\", \"batchId\"], \"data\": [\n" + structure + "]},\n"
           "  \"forceField\": {\n" + forceField + "}}}\n";
}

const char* kOpenBox = "\"inf\", 0, \"inf\"";
const std::string kAllPairs = "\"all\": {\"type\": [\"NBody\", \"all\"]},\n";
const std::string kCoulomb = kAllPairs + "\"coulomb\": {\"type\": [\"NonBonded\", \"Coulomb\"], "
                                         "\"parameters\": {\"dielectricConstant\": 2.5, \"condition\": \"all\"}}";
std::string gravity(double G, double softening) {
    return kAllPairs + "\"gravity\": {\"type\": [\"NonBonded\", \"Gravity\"], \"parameters\": {\"G\": " + number(G) +
           ", \"softening\": " + number(softening) + ", \"condition\": \"all\"}}";
}

// n bodies in a cube of side `side` about the origin, no two closer than `closest`, with charges in
// [-2, 2], masses in [0.5, 2] and velocities of spread `speed`.
std::vector<Body> random_bodies(int n, double side, double closest, double speed, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<Body> bodies;
    while (static_cast<int>(bodies.size()) < n) {
        Body b{{rng.uniform(-side / 2, side / 2), rng.uniform(-side / 2, side / 2), rng.uniform(-side / 2, side / 2)},
               {speed * rng.normal(), speed * rng.normal(), speed * rng.normal()},
               rng.uniform(0.5, 2.0),
               rng.uniform(-2.0, 2.0),
               0};
        bool apart = true;
        for (const Body& other : bodies) {
            double r2 = 0;
            for (int d = 0; d < 3; ++d) r2 += (b.position[d] - other.position[d]) * (b.position[d] - other.position[d]);
            apart = apart && r2 > closest * closest;
        }
        if (apart) bodies.push_back(b);
    }
    return bodies;
}

SimHandle load(const std::string& input) {
    structmd_sim* raw = nullptr;
    if (structmd_create(create_options(g_backend, "double").c_str(), &raw) != STRUCTMD_OK) {
        ADD_FAILURE() << structmd_last_error(nullptr);
        return nullptr;
    }
    SimHandle sim(raw);
    if (structmd_load_string(sim.get(), input.c_str()) != STRUCTMD_OK) {
        ADD_FAILURE() << structmd_last_error(sim.get());
        return nullptr;
    }
    return sim;
}

// The error of loading `input`, or "" when it loads.
std::string load_error(const std::string& input) {
    structmd_sim* raw = nullptr;
    if (structmd_create(create_options(g_backend, "double").c_str(), &raw) != STRUCTMD_OK) return "no handle";
    SimHandle sim(raw);
    if (structmd_load_string(sim.get(), input.c_str()) == STRUCTMD_OK) return "";
    return structmd_last_error(sim.get());
}

// The direct sum of a pair potential U(r) = k p_i p_j / s(r), s = sqrt(r^2 + eps^2), over every pair of
// a batch, in an open box: k = 1/eps_r and p the charges (Coulomb), or k = -G and p the masses.
struct DirectSum {
    double energy = 0.0;
    std::vector<double> forces;
    std::array<double, 9> virial{};
};

DirectSum direct_sum(const std::vector<Body>& bodies, double k, double softening, bool masses) {
    DirectSum sum;
    sum.forces.assign(3 * bodies.size(), 0.0);
    for (size_t i = 0; i < bodies.size(); ++i)
        for (size_t j = i + 1; j < bodies.size(); ++j) {
            if (bodies[i].batch != bodies[j].batch) continue;
            double d[3], r2 = softening * softening;
            for (int a = 0; a < 3; ++a) {
                d[a] = bodies[i].position[a] - bodies[j].position[a];
                r2 += d[a] * d[a];
            }
            const double s = std::sqrt(r2);
            const double product = masses ? bodies[i].mass * bodies[j].mass : bodies[i].charge * bodies[j].charge;
            const double u = k * product / s;
            sum.energy += u;
            // F_i = -dU/dr_i = (U / s^2) (r_i - r_j)
            for (int a = 0; a < 3; ++a) {
                const double f = u / r2 * d[a];
                sum.forces[3 * i + a] += f;
                sum.forces[3 * j + a] -= f;
                for (int b = 0; b < 3; ++b) sum.virial[3 * a + b] += d[a] * u / r2 * d[b];
            }
        }
    return sum;
}

std::vector<double> forces_of(structmd_sim* sim, size_t n) {
    std::vector<double> f(3 * n);
    EXPECT_EQ(structmd_get_forces(sim, f.data(), static_cast<int64_t>(n)), STRUCTMD_OK) << structmd_last_error(sim);
    return f;
}

double potential_of(structmd_sim* sim) {
    double e = 0;
    EXPECT_EQ(structmd_get_energy(sim, "potential", &e), STRUCTMD_OK) << structmd_last_error(sim);
    return e;
}

TEST(NBody, CoulombInAnOpenBoxIsTheDirectSum) {
    const std::vector<Body> bodies = random_bodies(50, 12.0, 0.7, 0.0, 11);
    SimHandle sim = load(document(bodies, kOpenBox, kCoulomb));
    ASSERT_TRUE(sim);
    const DirectSum expected = direct_sum(bodies, 1.0 / 2.5, 0.0, false);
    EXPECT_LT(relative_deviation(potential_of(sim.get()), expected.energy), 1e-12);
    EXPECT_LT(max_relative_deviation(forces_of(sim.get(), bodies.size()), expected.forces), 1e-12);
    std::array<double, 9> w{};
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_virial(sim.get(), w.data()));
    EXPECT_LT(tensor_relative_deviation(w, expected.virial), 1e-12);
    // "inf" and 0 are open axes, read back as infinity, along which no position is wrapped.
    std::array<double, 3> lengths{};
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_box(sim.get(), lengths.data()));
    for (double l : lengths) EXPECT_TRUE(std::isinf(l) && l > 0) << l;
    std::vector<double> xyz(3 * bodies.size());
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_positions(sim.get(), xyz.data(), static_cast<int64_t>(bodies.size())));
    for (size_t i = 0; i < bodies.size(); ++i)
        for (int a = 0; a < 3; ++a) EXPECT_EQ(xyz[3 * i + a], bodies[i].position[a]);
}

TEST(NBody, CoulombForcesAreMinusTheEnergysGradient) {
    std::vector<Body> bodies = random_bodies(12, 6.0, 0.8, 0.0, 5);
    SimHandle sim = load(document(bodies, kOpenBox, kCoulomb));
    ASSERT_TRUE(sim);
    const std::vector<double> forces = forces_of(sim.get(), bodies.size());
    std::vector<double> xyz;
    for (const Body& b : bodies) xyz.insert(xyz.end(), b.position.begin(), b.position.end());
    const double h = 1e-5;
    double worst = 0;
    for (size_t c = 0; c < xyz.size(); ++c) {
        std::vector<double> moved = xyz;
        moved[c] = xyz[c] + h;
        ASSERT_STRUCTMD_OK(sim.get(), structmd_set_positions(sim.get(), moved.data(), static_cast<int64_t>(bodies.size())));
        const double up = potential_of(sim.get());
        moved[c] = xyz[c] - h;
        ASSERT_STRUCTMD_OK(sim.get(), structmd_set_positions(sim.get(), moved.data(), static_cast<int64_t>(bodies.size())));
        const double down = potential_of(sim.get());
        worst = std::max(worst, std::abs(-(up - down) / (2 * h) - forces[c]));
    }
    EXPECT_LT(worst / max_abs(forces), 1e-7);
}

// A cluster of 24 bodies bound by softened gravity, at rest on the whole: velocity Verlet keeps the total
// energy to a small drift and the momentum to round-off, and the potential at the start is the direct sum.
TEST(NBody, GravitationalClusterConservesEnergyAndMomentum) {
    std::vector<Body> bodies = random_bodies(24, 4.0, 0.3, 0.3, 7);
    Vec3 momentum{0, 0, 0};
    double mass = 0;
    for (const Body& b : bodies) {
        for (int a = 0; a < 3; ++a) momentum[a] += b.mass * b.velocity[a];
        mass += b.mass;
    }
    for (Body& b : bodies)
        for (int a = 0; a < 3; ++a) b.velocity[a] -= momentum[a] / mass;
    const double G = 0.5, softening = 0.2;
    SimHandle sim = load(document(bodies, "0, 0, 0", gravity(G, softening), 2e-3));
    ASSERT_TRUE(sim);
    const DirectSum expected = direct_sum(bodies, -G, softening, true);
    EXPECT_LT(relative_deviation(potential_of(sim.get()), expected.energy), 1e-12);
    EXPECT_LT(max_relative_deviation(forces_of(sim.get(), bodies.size()), expected.forces), 1e-12);
    const auto total = [&] {
        double kinetic = 0;
        EXPECT_EQ(structmd_get_energy(sim.get(), "kinetic", &kinetic), STRUCTMD_OK) << structmd_last_error(sim.get());
        return kinetic + potential_of(sim.get());
    };
    const double start = total();
    ASSERT_LT(start, 0.0) << "the cluster should be bound";
    double drift = 0;
    for (int block = 0; block < 20; ++block) {
        ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), 100));
        drift = std::max(drift, std::abs(total() - start));
    }
    EXPECT_LT(drift / std::abs(start), 2e-4);
    std::vector<double> v(3 * bodies.size());
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_velocities(sim.get(), v.data(), static_cast<int64_t>(bodies.size())));
    double speed = 0;
    Vec3 p{0, 0, 0};
    for (size_t i = 0; i < bodies.size(); ++i)
        for (int a = 0; a < 3; ++a) {
            p[a] += bodies[i].mass * v[3 * i + a];
            speed = std::max(speed, std::abs(v[3 * i + a]));
        }
    for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(p[a]), 1e-12 * mass * speed) << "momentum " << a;
}

// Two systems overlaid in one open box (batchId 0 and 1) never interact: the energy and forces are
// those of each batch's own direct sum.
TEST(NBody, BatchesNeverPair) {
    std::vector<Body> bodies = random_bodies(30, 5.0, 0.6, 0.0, 3);
    for (size_t i = 0; i < bodies.size(); ++i) bodies[i].batch = i < 13 ? 0 : 1;
    SimHandle sim = load(document(bodies, kOpenBox, kCoulomb));
    ASSERT_TRUE(sim);
    const DirectSum expected = direct_sum(bodies, 1.0 / 2.5, 0.0, false);
    EXPECT_LT(relative_deviation(potential_of(sim.get()), expected.energy), 1e-12);
    EXPECT_LT(max_relative_deviation(forces_of(sim.get(), bodies.size()), expected.forces), 1e-12);
}

// Any pair potential may run over all pairs: Debye-Hueckel in a periodic box over an NBody entry gives
// what it gives over a Verlet list (each pair at its nearest image, within the cutoff).
TEST(NBody, ScreenedTermOverAllPairsIsTheVerletListsTerm) {
    std::vector<Body> bodies = random_bodies(60, 9.0, 0.7, 0.0, 13);
    const std::string term = "\"dh\": {\"type\": [\"NonBonded\", \"DebyeHuckel\"], \"parameters\": {\"cutOffFactor\": 3.0, "
                             "\"dielectricConstant\": 1.5, \"debyeLength\": 1.2, \"condition\": \"all\", "
                             "\"neighbourList\": \"list\"}}";
    SimHandle overAll = load(document(bodies, "9, 9, 9", "\"list\": {\"type\": [\"NBody\", \"all\"]},\n" + term));
    SimHandle overList = load(document(
        bodies, "9, 9, 9", "\"list\": {\"type\": [\"VerletConditionalListSet\", \"all\"]},\n" + term));
    ASSERT_TRUE(overAll && overList);
    EXPECT_LT(relative_deviation(potential_of(overAll.get()), potential_of(overList.get())), 1e-12);
    EXPECT_LT(max_relative_deviation(forces_of(overAll.get(), bodies.size()), forces_of(overList.get(), bodies.size())),
              1e-12);
    std::array<double, 9> a{}, b{};
    ASSERT_STRUCTMD_OK(overAll.get(), structmd_get_virial(overAll.get(), a.data()));
    ASSERT_STRUCTMD_OK(overList.get(), structmd_get_virial(overList.get(), b.data()));
    EXPECT_LT(tensor_relative_deviation(a, b), 1e-12);
}

const std::string kScreened = "\"dh\": {\"type\": [\"NonBonded\", \"DebyeHuckel\"], \"parameters\": {\"cutOffFactor\": 2.0, "
                              "\"dielectricConstant\": 1.0, \"debyeLength\": 1.0, \"condition\": \"all\", "
                              "\"neighbourList\": \"list\"}}";
const std::string kScreenedOverVerletLists =
    "\"list\": {\"type\": [\"VerletConditionalListSet\", \"all\"]},\n" + kScreened;
const std::string kScreenedOverAllPairs = "\"list\": {\"type\": [\"NBody\", \"all\"]},\n" + kScreened;

// Charges of one sign: the screened term then only pushes the bodies apart, and a run stays finite.
std::vector<Body> repelling(std::vector<Body> bodies) {
    for (Body& b : bodies) b.charge = std::abs(b.charge) + 0.1;
    return bodies;
}

std::vector<double> positions_of(structmd_sim* sim, size_t n) {
    std::vector<double> x(3 * n);
    EXPECT_EQ(structmd_get_positions(sim, x.data(), static_cast<int64_t>(n)), STRUCTMD_OK) << structmd_last_error(sim);
    return x;
}

// The same term over a Verlet list and over all pairs, at the Verlet run's positions: energy, forces
// and virial agree to rounding.
void expect_lists_find_every_pair(structmd_sim* listed, structmd_sim* allPairs, size_t n, const std::string& when) {
    const std::vector<double> x = positions_of(listed, n);
    ASSERT_STRUCTMD_OK(allPairs, structmd_set_positions(allPairs, x.data(), static_cast<int64_t>(n)));
    EXPECT_LT(relative_deviation(potential_of(listed), potential_of(allPairs)), 1e-12) << when;
    EXPECT_LT(max_relative_deviation(forces_of(listed, n), forces_of(allPairs, n)), 1e-12) << when;
    std::array<double, 9> a{}, b{};
    ASSERT_STRUCTMD_OK(listed, structmd_get_virial(listed, a.data()));
    ASSERT_STRUCTMD_OK(allPairs, structmd_get_virial(allPairs, b.data()));
    EXPECT_LT(tensor_relative_deviation(a, b), 1e-12) << when;
}

// Verlet lists over open axes: cells repeat along them, so a clump far up an open axis shares cells
// with one near the origin. The lists must still hold every pair within reach and no other, after the
// load and after a run long enough to rebuild them, in a box open along every axis and in a slab.
TEST(NBody, VerletListsOverOpenAxesFindEveryPair) {
    std::vector<Body> bodies = repelling(random_bodies(70, 6.0, 0.75, 0.8, 31));
    std::vector<Body> far = repelling(random_bodies(40, 5.0, 0.75, 0.8, 32));
    for (Body& b : far) {
        b.position[2] += 701.3;
        bodies.push_back(b);
    }
    const size_t n = bodies.size();
    for (const char* box : {"\"inf\", \"inf\", \"inf\"", "7.5, 7.5, \"inf\"", "0, 9, 0"}) {
        SimHandle listed = load(document(bodies, box, kScreenedOverVerletLists, 5e-3));
        SimHandle allPairs = load(document(bodies, box, kScreenedOverAllPairs, 5e-3));
        ASSERT_TRUE(listed && allPairs) << box;
        expect_lists_find_every_pair(listed.get(), allPairs.get(), n, std::string("at the load, box ") + box);
        ASSERT_STRUCTMD_OK(listed.get(), structmd_step(listed.get(), 400));
        char counters[512];
        ASSERT_STRUCTMD_OK(listed.get(), structmd_get_counters(listed.get(), counters, sizeof counters));
        const std::string text = counters;
        const size_t at = text.find("\"neighbour_list_builds\":");
        ASSERT_NE(at, std::string::npos) << text;
        EXPECT_GT(std::stoll(text.substr(at + 24)), 2) << "the run must rebuild the lists: " << text;
        expect_lists_find_every_pair(listed.get(), allPairs.get(), n, std::string("after 400 steps, box ") + box);
        const std::vector<double> x = positions_of(listed.get(), n);
        for (double c : x) ASSERT_TRUE(std::isfinite(c));
    }
}

// A run continued from a checkpoint follows the uninterrupted run.
void expect_checkpoint_round_trip(const std::string& input, size_t n, const std::string& name) {
    const std::string path = ::testing::TempDir() + name + "_" + g_backend + ".chk";
    SimHandle first = load(input);
    ASSERT_TRUE(first);
    ASSERT_STRUCTMD_OK(first.get(), structmd_step(first.get(), 50));
    ASSERT_STRUCTMD_OK(first.get(), structmd_save_checkpoint(first.get(), path.c_str()));
    ASSERT_STRUCTMD_OK(first.get(), structmd_step(first.get(), 50));
    SimHandle second = load(input);
    ASSERT_TRUE(second);
    ASSERT_STRUCTMD_OK(second.get(), structmd_load_checkpoint(second.get(), path.c_str()));
    std::array<double, 3> saved{}, restored{};
    ASSERT_STRUCTMD_OK(first.get(), structmd_get_box(first.get(), saved.data()));
    ASSERT_STRUCTMD_OK(second.get(), structmd_get_box(second.get(), restored.data()));
    EXPECT_EQ(restored, saved);
    EXPECT_TRUE(std::isinf(restored[0]) && std::isinf(restored[2])) << restored[0] << " " << restored[2];
    ASSERT_STRUCTMD_OK(second.get(), structmd_step(second.get(), 50));
    std::vector<double> a(3 * n), b(3 * n);
    ASSERT_STRUCTMD_OK(first.get(), structmd_get_positions(first.get(), a.data(), static_cast<int64_t>(n)));
    ASSERT_STRUCTMD_OK(second.get(), structmd_get_positions(second.get(), b.data(), static_cast<int64_t>(n)));
    for (size_t c = 0; c < a.size(); ++c) {
        EXPECT_TRUE(std::isfinite(a[c]));
        EXPECT_EQ(a[c], b[c]) << "coordinate " << c;
    }
    std::remove(path.c_str());
}

// A checkpoint of an open box restores it, with pairs over all pairs or over Verlet lists.
TEST(NBody, OpenBoxCheckpointRoundTrip) {
    const std::vector<Body> bodies = random_bodies(16, 4.0, 0.4, 0.3, 21);
    expect_checkpoint_round_trip(document(bodies, "\"inf\", \"inf\", \"inf\"", gravity(1.0, 0.1)), bodies.size(),
                                 "nbody_open_box");
    const std::vector<Body> liquid = repelling(random_bodies(40, 5.0, 0.75, 0.8, 22));
    expect_checkpoint_round_trip(document(liquid, "\"inf\", 6, \"inf\"", kScreenedOverVerletLists, 5e-3), liquid.size(),
                                 "verlet_open_box");
}

// structmd_set_box takes 0 or infinity as an open axis (kept as infinity); a position along an axis
// made open stays where it was; a negative length is refused, naming its index.
TEST(NBody, SetBoxOpensAnAxis) {
    std::vector<Body> bodies = random_bodies(8, 3.0, 0.5, 0.0, 2);
    SimHandle sim = load(document(bodies, "20, 20, 20",
                                  kAllPairs + "\"dh\": {\"type\": [\"NonBonded\", \"DebyeHuckel\"], \"parameters\": "
                                              "{\"cutOffFactor\": 2.0, \"dielectricConstant\": 1.0, \"debyeLength\": 1.0, "
                                              "\"condition\": \"all\"}}"));
    ASSERT_TRUE(sim);
    const size_t n = bodies.size();
    std::vector<double> before(3 * n), after(3 * n);
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_positions(sim.get(), before.data(), static_cast<int64_t>(n)));
    const double open[3] = {0.0, std::numeric_limits<double>::infinity(), 40.0};
    ASSERT_STRUCTMD_OK(sim.get(), structmd_set_box(sim.get(), open));
    std::array<double, 3> lengths{};
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_box(sim.get(), lengths.data()));
    EXPECT_TRUE(std::isinf(lengths[0]) && std::isinf(lengths[1]));
    EXPECT_EQ(lengths[2], 40.0);
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_positions(sim.get(), after.data(), static_cast<int64_t>(n)));
    for (size_t i = 0; i < n; ++i) {
        EXPECT_DOUBLE_EQ(after[3 * i], before[3 * i]);
        EXPECT_DOUBLE_EQ(after[3 * i + 1], before[3 * i + 1]);
        EXPECT_DOUBLE_EQ(after[3 * i + 2], 2.0 * before[3 * i + 2]);
    }
    ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), 10));
    const double bad[3] = {10.0, -1.0, 10.0};
    EXPECT_EQ(structmd_set_box(sim.get(), bad), STRUCTMD_ERR_ARGUMENT);
    EXPECT_NE(std::string(structmd_last_error(sim.get())).find("lengths[1]"), std::string::npos)
        << structmd_last_error(sim.get());
    // A term over Verlet lists: the lists are laid out again for the opened axes and find the pairs
    // all pairs find.
    SimHandle listed = load(document(bodies, "20, 20, 20", kScreenedOverVerletLists));
    SimHandle allPairs = load(document(bodies, "20, 20, 20", kScreenedOverAllPairs));
    ASSERT_TRUE(listed && allPairs);
    ASSERT_STRUCTMD_OK(listed.get(), structmd_step(listed.get(), 10));
    ASSERT_STRUCTMD_OK(listed.get(), structmd_set_box(listed.get(), open));
    ASSERT_STRUCTMD_OK(allPairs.get(), structmd_set_box(allPairs.get(), open));
    ASSERT_STRUCTMD_OK(listed.get(), structmd_get_box(listed.get(), lengths.data()));
    EXPECT_TRUE(std::isinf(lengths[0]) && std::isinf(lengths[1]));
    ASSERT_STRUCTMD_OK(listed.get(), structmd_step(listed.get(), 10));
    expect_lists_find_every_pair(listed.get(), allPairs.get(), n, "after opening two axes");
}

void expect_error(const std::string& input, const std::vector<std::string>& fragments) {
    const std::string error = load_error(input);
    ASSERT_FALSE(error.empty()) << "loaded, expected an error containing " << fragments.front();
    for (const std::string& fragment : fragments)
        EXPECT_NE(error.find(fragment), std::string::npos) << "error: " << error << "\nexpected: " << fragment;
}

TEST(NBody, RefusedInputsNameTheirPath) {
    const std::vector<Body> bodies = random_bodies(6, 3.0, 0.5, 0.0, 4);
    expect_error(document(bodies, "10, -2, 10", kCoulomb),
                 {"global.ensemble.data[0][0][1]", "box length must be > 0 and <= 1e15, or 0 or \"inf\""});
    expect_error(document(bodies, "10, \"wide\", 10", kCoulomb), {"global.ensemble.data[0][0][1]"});
    expect_error(document(bodies, "10, 10, 1e300", kCoulomb), {"global.ensemble.data[0][0][2]"});
    // Unscreened Coulomb over a periodic axis would miss the periodic sum.
    expect_error(document(bodies, "10, 10, \"inf\"", kCoulomb),
                 {"global.ensemble.data[0][0]", "[\"NonBonded\", \"Coulomb\"]", "open along every axis"});
    // A term of no finite range over a Verlet list would be cut at the list's radius.
    expect_error(document(bodies, kOpenBox,
                          "\"nl\": {\"type\": [\"VerletConditionalListSet\", \"all\"]},\n"
                          "\"coulomb\": {\"type\": [\"NonBonded\", \"Coulomb\"], \"parameters\": "
                          "{\"dielectricConstant\": 1.0, \"condition\": \"all\"}}"),
                 {"topology.forceField.nl.type", "acts at every distance"});
    expect_error(document(bodies, kOpenBox,
                          kAllPairs + "\"g\": {\"type\": [\"NonBonded\", \"Gravity\"], \"parameters\": "
                                      "{\"G\": -1.0, \"condition\": \"all\"}}"),
                 {"topology.forceField.g.parameters.G"});
    expect_error(document(bodies, kOpenBox,
                          kAllPairs + "\"g\": {\"type\": [\"NonBonded\", \"Gravity\"], \"parameters\": "
                                      "{\"G\": 1.0, \"cutOffFactor\": 2.0, \"condition\": \"all\"}}"),
                 {"topology.forceField.g.parameters.cutOffFactor"});
    expect_error(document(bodies, kOpenBox,
                          "\"all\": {\"type\": [\"NBody\", \"intra_inter\"]},\n"
                          "\"coulomb\": {\"type\": [\"NonBonded\", \"Coulomb\"], \"parameters\": "
                          "{\"dielectricConstant\": 1.0, \"condition\": \"all\"}}"),
                 {"topology.forceField.all.type"});
    expect_error(document(bodies, "20, 20, 20", gravity(1.0, 0.1)),
                 {"global.ensemble.data[0][0]", "[\"NonBonded\", \"Gravity\"]", "open along every axis"});
}

}  // namespace
}  // namespace structmd_physics

int main(int argc, char** argv) { return structmd_physics::run_tests_on_backend(argc, argv, structmd_physics::g_backend); }
