// The Transverser contract (src/transverser/) on the CPU backend: transversers written by a user
// (a neighbour counter, a local density, a Lennard-Jones force with its virial) and the expression
// transverser, over a neighbour list and over all pairs, each against a direct double loop over
// every pair, in a periodic box and in an open one (over lists and over all pairs).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "expression/compiler.hpp"
#include "expression/parser.hpp"
#include "forcefield/expression_potentials.hpp"
#include "neighbour/verlet_list.hpp"
#include "transverser/all_pairs_traversal.hpp"
#include "transverser/expression_sum.hpp"
#include "transverser/neighbour_traversal.hpp"

namespace structmd {
namespace {

// How many neighbours each particle has within the traversal's reach; Info: the index, to check
// that info() is asked of the right particles.
struct NeighbourCounter {
    using Info = int;
    using Compute = int;
    int* count;
    SMD_HD int zero() const { return 0; }
    SMD_HD int info(int i) const { return i; }
    SMD_HD int compute(const Real4<double>&, const Real4<double>&, int i, int j) const { return i != j ? 1 : 1000; }
    SMD_HD void accumulate(int& total, int current) const { total += current; }
    SMD_HD void set(int i, int total) const { count[i] = total; }
};

// sum_j m_j w(r_ij) with w(r) = (1 - r / h)^2 for r < h: a local density weighted by the masses
// (Info) and, for type 1, twice (the type in w of the position).
struct LocalDensity {
    using Info = double;
    using Compute = double;
    const double* mass;
    double h;
    double* density;
    SMD_HD double zero() const { return 0; }
    SMD_HD double info(int i) const { return mass[i]; }
    SMD_HD double compute(const Real4<double>& ri, const Real4<double>& rj, double, double mj) const {
        const Vec3<double> d = xyz(rj) - xyz(ri);
        const double r = std::sqrt(dot(d, d));
        const double w = r < h ? (1 - r / h) * (1 - r / h) : 0.0;
        return (rj.w == 1 ? 2.0 : 1.0) * mj * w;
    }
    SMD_HD void accumulate(double& total, double current) const { total += current; }
    SMD_HD void set(int i, double total) const { density[i] = total; }
};

// The Lennard-Jones force and virial on each particle (eps = sigma = 1): a pair potential as a
// transverser, whose Compute is a structure.
struct LennardJonesForce {
    struct Compute {
        Vec3<double> force;
        double virial;  // trace: sum over pairs of r . f / 2
    };
    struct Info {};
    double cutoff2;
    Compute* out;
    SMD_HD Compute zero() const { return {{0, 0, 0}, 0}; }
    SMD_HD Info info(int) const { return {}; }
    SMD_HD Compute compute(const Real4<double>& ri, const Real4<double>& rj, Info, Info) const {
        const Vec3<double> d = xyz(rj) - xyz(ri);
        const double r2 = dot(d, d);
        if (r2 >= cutoff2) return zero();
        const double s6 = 1 / (r2 * r2 * r2);
        const double fOverR = 24 * (2 * s6 * s6 - s6) / r2;  // |f| / r, repulsive positive
        return {(-fOverR) * d, 0.5 * fOverR * r2};
    }
    SMD_HD void accumulate(Compute& total, const Compute& c) const {
        total.force += c.force;
        total.virial += c.virial;
    }
    SMD_HD void set(int i, const Compute& total) const { out[i] = total; }
};

struct System {
    CpuBackend backend{2};
    Box<double> box;
    HostBuffer<Real4<double>> pos;
    std::vector<double> mass;
    std::vector<uint8_t> group;
    int64_t n;

    System(int64_t count, double length, unsigned seed, bool open = false) : n(count) {
        const double inf = std::numeric_limits<double>::infinity();
        box = open ? Box<double>{{inf, inf, inf}, {0, 0, 0}} : Box<double>::make(length, length, length);
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(-0.5, 0.5);
        backend.resize(pos, n);
        for (int64_t i = 0; i < n; ++i) {
            pos.data()[i] = {u(rng) * length, u(rng) * length, u(rng) * length, double(i % 2)};
            mass.push_back(1.0 + 0.5 * static_cast<double>(i % 3));
            group.push_back(i % 5 != 0);
        }
    }

    Vec3<double> separation(int64_t i, int64_t j) const {
        return box.minimum_image(xyz(pos.data()[j]) - xyz(pos.data()[i]));
    }

    // visit(i, j, d) for every ordered pair within the cutoff (all pairs for infinity), by brute force.
    template <class Visit>
    void each_pair(double cutoff, const uint8_t* members, Visit visit) const {
        for (int64_t i = 0; i < n; ++i)
            for (int64_t j = 0; j < n; ++j) {
                if (i == j || (members && (!members[i] || !members[j]))) continue;
                const Vec3<double> d = separation(i, j);
                if (dot(d, d) < cutoff * cutoff) visit(i, j, d);
            }
    }

    template <class T>
    void over_list(const T& t, double cutoff, const uint8_t* members) {
        VerletList<CpuBackend, double> list(backend, cutoff, 1.2, PairCondition::all, PairFilterInputs{}, nullptr, 1,
                                            nullptr);
        list.update(pos, n, box, 1);
        backend.for_each_lanes(n, NeighbourTraversal<T, double>{t, list.view(), cutoff * cutoff, members});
    }

    template <class T>
    void over_all_pairs(const T& t, const uint8_t* members, const int* batch = nullptr) {
        backend.for_each_lanes(n, AllPairsTraversal<T, double>{t, pos.data(), n, box, members, batch});
    }
};

// Each particle's neighbour count over the list against the brute-force count; returns the pairs
// counted, so a test can check its system is dense enough for the comparison to mean something.
int64_t expect_list_counts_every_neighbour(System& s, double cutoff) {
    std::vector<int> count(s.n, -1), expected(s.n, 0);
    s.over_list(NeighbourCounter{count.data()}, cutoff, nullptr);
    s.each_pair(cutoff, nullptr, [&](int64_t i, int64_t, const Vec3<double>&) { ++expected[i]; });
    int64_t pairs = 0;
    for (int64_t i = 0; i < s.n; ++i) {
        EXPECT_EQ(count[i], expected[i]) << "particle " << i;
        pairs += expected[i];
    }
    return pairs;
}

TEST(NeighbourTraversal, CountsTheNeighboursOfEveryParticle) {
    System s(700, 10.0, 1);
    EXPECT_GT(expect_list_counts_every_neighbour(s, 1.7), 4 * s.n);
}

// Over open axes the list's cells repeat: every third particle moved 503.7 up z (and a few far down x)
// shares cells with those left near the origin, and the counts must still be the brute-force ones.
TEST(NeighbourTraversal, CountsTheNeighboursInAnOpenBox) {
    System s(700, 10.0, 1, true);
    for (int64_t i = 0; i < s.n; i += 3) s.pos.data()[i].z += 503.7;
    for (int64_t i = 0; i < s.n; i += 50) s.pos.data()[i].x -= 1.0e4;
    EXPECT_GT(expect_list_counts_every_neighbour(s, 1.7), 2 * s.n);
}

TEST(NeighbourTraversal, LeavesParticlesOutsideTheGroupAloneAndSkipsTheirPairs) {
    System s(500, 9.0, 2);
    const double cutoff = 2.0;
    std::vector<int> count(s.n, -1), expected(s.n, 0);
    s.over_list(NeighbourCounter{count.data()}, cutoff, s.group.data());
    s.each_pair(cutoff, s.group.data(), [&](int64_t i, int64_t, const Vec3<double>&) { ++expected[i]; });
    for (int64_t i = 0; i < s.n; ++i) EXPECT_EQ(count[i], s.group[i] ? expected[i] : -1) << "particle " << i;
}

TEST(NeighbourTraversal, LocalDensityReadsInfoAndTypes) {
    System s(600, 9.0, 3);
    const double h = 1.5;
    std::vector<double> density(s.n), expected(s.n, 0.0);
    s.over_list(LocalDensity{s.mass.data(), h, density.data()}, h, nullptr);
    s.each_pair(h, nullptr, [&](int64_t i, int64_t j, const Vec3<double>& d) {
        const double r = std::sqrt(dot(d, d));
        expected[i] += (j % 2 == 1 ? 2.0 : 1.0) * s.mass[j] * (1 - r / h) * (1 - r / h);
    });
    for (int64_t i = 0; i < s.n; ++i) EXPECT_NEAR(density[i], expected[i], 1e-12 * (1 + expected[i])) << i;
}

TEST(NeighbourTraversal, LennardJonesForceAsATransverser) {
    System s(400, 8.0, 4);
    const double cutoff = 2.5;
    std::vector<LennardJonesForce::Compute> out(s.n);
    s.over_list(LennardJonesForce{cutoff * cutoff, out.data()}, cutoff, nullptr);
    std::vector<Vec3<double>> force(s.n, Vec3<double>{0, 0, 0});
    std::vector<double> virial(s.n, 0.0);
    s.each_pair(cutoff, nullptr, [&](int64_t i, int64_t, const Vec3<double>& d) {
        const double r2 = dot(d, d), r = std::sqrt(r2);
        // U = 4 (r^-12 - r^-6); the force on i is dU/dr d / r (d points from i to j).
        const double dudr = 4 * (-12 * std::pow(r, -13) + 6 * std::pow(r, -7));
        force[i] += (dudr / r) * d;
        virial[i] += -0.5 * dudr * r;
    });
    for (int64_t i = 0; i < s.n; ++i) {
        const double scale = 1e-10 * (1 + std::sqrt(dot(force[i], force[i])));
        EXPECT_NEAR(out[i].force.x, force[i].x, scale) << i;
        EXPECT_NEAR(out[i].force.y, force[i].y, scale) << i;
        EXPECT_NEAR(out[i].force.z, force[i].z, scale) << i;
        EXPECT_NEAR(out[i].virial, virial[i], 1e-10 * (1 + std::abs(virial[i]))) << i;
    }
}

TEST(AllPairsTraversal, VisitsEveryOtherParticleOfTheGroupByMinimumImage) {
    System s(300, 6.0, 5);
    std::vector<LennardJonesForce::Compute> out(s.n);
    std::vector<int> count(s.n, -1);
    s.over_all_pairs(NeighbourCounter{count.data()}, s.group.data());
    int64_t members = 0;
    for (uint8_t g : s.group) members += g;
    for (int64_t i = 0; i < s.n; ++i) EXPECT_EQ(count[i], s.group[i] ? members - 1 : -1) << i;
    // With a cutoff of its own the same traversal gives the list's answer.
    const double cutoff = 2.5;
    std::vector<LennardJonesForce::Compute> listed(s.n);
    s.over_all_pairs(LennardJonesForce{cutoff * cutoff, out.data()}, nullptr);
    s.over_list(LennardJonesForce{cutoff * cutoff, listed.data()}, cutoff, nullptr);
    for (int64_t i = 0; i < s.n; ++i) {
        EXPECT_NEAR(out[i].force.x, listed[i].force.x, 1e-9 * (1 + std::abs(listed[i].force.x))) << i;
        EXPECT_NEAR(out[i].virial, listed[i].virial, 1e-9 * (1 + std::abs(listed[i].virial))) << i;
    }
}

TEST(AllPairsTraversal, KeepsBatchesApart) {
    System s(240, 6.0, 8);
    std::vector<int> batch(s.n), count(s.n, -1);
    for (int64_t i = 0; i < s.n; ++i) batch[i] = static_cast<int>((i * 7) % 3);
    s.over_all_pairs(NeighbourCounter{count.data()}, s.group.data(), batch.data());
    for (int64_t i = 0; i < s.n; ++i) {
        int expected = 0;
        for (int64_t j = 0; j < s.n; ++j) expected += j != i && s.group[j] && batch[j] == batch[i];
        EXPECT_EQ(count[i], s.group[i] ? expected : -1) << i;
    }
}

// Gravity in an open box: sum over all j of m_j / r_ij^2 along d, no cutoff, no images.
struct Gravity {
    using Info = double;
    using Compute = Vec3<double>;
    const double* mass;
    Vec3<double>* out;
    SMD_HD Compute zero() const { return {0, 0, 0}; }
    SMD_HD double info(int i) const { return mass[i]; }
    SMD_HD Compute compute(const Real4<double>& ri, const Real4<double>& rj, double mi, double mj) const {
        const Vec3<double> d = xyz(rj) - xyz(ri);
        const double r2 = dot(d, d);
        return (mi * mj / (r2 * std::sqrt(r2))) * d;
    }
    SMD_HD void accumulate(Compute& total, const Compute& c) const { total += c; }
    SMD_HD void set(int i, const Compute& total) const { out[i] = total; }
};

TEST(AllPairsTraversal, GravityInAnOpenBoxSeesNoImages) {
    System s(200, 20.0, 6, true);
    std::vector<Vec3<double>> out(s.n);
    s.over_all_pairs(Gravity{s.mass.data(), out.data()}, nullptr);
    Vec3<double> total{0, 0, 0};
    for (int64_t i = 0; i < s.n; ++i) {
        Vec3<double> expected{0, 0, 0};
        for (int64_t j = 0; j < s.n; ++j) {
            if (j == i) continue;
            const Vec3<double> d = xyz(s.pos.data()[j]) - xyz(s.pos.data()[i]);  // no minimum image
            expected += (s.mass[i] * s.mass[j] / std::pow(dot(d, d), 1.5)) * d;
        }
        EXPECT_NEAR(out[i].x, expected.x, 1e-10 * (1 + std::abs(expected.x))) << i;
        EXPECT_NEAR(out[i].y, expected.y, 1e-10 * (1 + std::abs(expected.y))) << i;
        EXPECT_NEAR(out[i].z, expected.z, 1e-10 * (1 + std::abs(expected.z))) << i;
        total += out[i];
    }
    EXPECT_NEAR(total.x, 0.0, 1e-9);  // Newton's third law
}

// The expression transverser, interpreted as the CPU backend runs it.
struct InterpretedSum {
    expression::Expression graph;
    expression::Program program;
    HostBuffer<expression::Instruction> code;
    HostBuffer<double> constants;

    InterpretedSum(const CpuBackend& backend, const std::string& text) {
        const std::vector<std::string> inputs = {"r",        "dx",       "dy",       "dz",     "type_i", "type_j",
                                                 "charge_i", "charge_j", "radius_i", "radius_j", "mass_i", "mass_j"};
        const int root = expression::parse(text, [&](const std::string& name) -> expression::Binding {
            for (size_t k = 0; k < inputs.size(); ++k)
                if (inputs[k] == name) return {expression::Binding::Kind::input, static_cast<int>(k), 0};
            return {};
        }, graph);
        program = expression::compile(graph, {root});
        std::vector<double> values = program.constants;
        values.push_back(0);
        backend.upload(code, program.code.data(), program.code.size());
        backend.upload(constants, values.data(), values.size());
    }

    ExpressionSum<InterpretedExpression, double> transverser(const double* charge, const double* radius,
                                                             const Real4<double>* velocities, double* out) const {
        InterpretedExpression::Params<double> p{};
        p.program = {code.data(), constants.data(), static_cast<int>(code.size())};
        return {p, charge, radius, velocities, out};
    }
};

TEST(ExpressionSum, CoordinationNumbersAndAWeightedSumOfThePairsInputs) {
    System s(500, 9.0, 7);
    std::vector<double> charge(s.n), radius(s.n);
    std::vector<Real4<double>> vel(s.n);
    for (int64_t i = 0; i < s.n; ++i) {
        charge[i] = (i % 3) - 1.0;
        radius[i] = 0.5 + 0.01 * static_cast<double>(i % 7);
        vel[i] = {0, 0, 0, s.mass[i]};
    }
    const double cutoff = 1.5;
    InterpretedSum coordination(s.backend, "r < 1.5");
    std::vector<double> count(s.n);
    s.over_list(coordination.transverser(nullptr, nullptr, nullptr, count.data()), 2.0, nullptr);
    std::vector<double> expected(s.n, 0.0);
    s.each_pair(cutoff, nullptr, [&](int64_t i, int64_t, const Vec3<double>&) { expected[i] += 1; });
    for (int64_t i = 0; i < s.n; ++i) EXPECT_EQ(count[i], expected[i]) << i;

    InterpretedSum weighted(s.backend, "charge_i * charge_j * exp(-r) + dx * mass_j + (type_j - type_i) * radius_j");
    std::vector<double> sum(s.n), reference(s.n, 0.0);
    s.over_all_pairs(weighted.transverser(charge.data(), radius.data(), vel.data(), sum.data()), nullptr);
    s.each_pair(std::numeric_limits<double>::infinity(), nullptr, [&](int64_t i, int64_t j, const Vec3<double>& d) {
        reference[i] += charge[i] * charge[j] * std::exp(-std::sqrt(dot(d, d))) + d.x * s.mass[j] +
                        (double(j % 2) - double(i % 2)) * radius[j];
    });
    for (int64_t i = 0; i < s.n; ++i) EXPECT_NEAR(sum[i], reference[i], 1e-9 * (1 + std::abs(reference[i]))) << i;
}

}  // namespace
}  // namespace structmd
