// The Verlet list never misses a pair within the cutoff, through the public C API: the list is built
// by a force evaluation, particles are then moved by velocity Verlet steps up to just under half the
// skin (no rebuild due) or just over it (a rebuild due), and the engine's forces and per-particle
// energies are compared with an all-pairs evaluation in double precision, for several skins.
//
// test_verlet_list.cpp checks the list's candidate pairs directly, for one skin and random moves of
// under 0.3 of the skin. This adds the worst cases the half-skin rule allows: pairs that approach
// each other head on by 0.49 of the skin each, so that a pair just inside the list radius ends just
// inside the cutoff; every particle moved by 0.45 to 0.499 of the skin; and pairs just outside the
// list radius that approach by 0.51 of the skin each, in one step or accumulated over five, which
// end inside the cutoff and are only found if the list is rebuilt.
//
// Particles have mass 1e12, so the forces deflect them by ~dt^2 F/m ~ 1e-14 and one step moves
// each by dt v: the test places them by choosing velocities (structmd_set_positions would force a
// rebuild). Usage: test_list_half_skin [--backend=cpu|cuda] [--precision=double|mixed]; with cuda it
// exits 77 (skipped) when no GPU is usable. Mixed precision runs the lists and pair kernel over
// cell-local positions in float (state/cell_local_positions.hpp) where the box has three cells or
// more along each axis (skins 0.1 and 0.3 here; the largest skin takes the double positions).
#include "stability_support.hpp"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace structmd_stability {
namespace {

std::string g_backend = "cpu";
std::string g_precision = "double";

constexpr double kCutoff = 2.5;
constexpr double kBoxLength = 9.0;
constexpr double kDensity = 0.7;
constexpr double kMinDistance = 0.85;
constexpr double kTimeStep = 0.01;
constexpr double kHeavyMass = 1e12;

// Both measures divide each particle's deviation by the sum of the magnitudes of its pair terms: the
// engine and the reference sum the same terms in other orders (rounding ~1e-14 of that sum), while a
// missing pair near the cutoff takes |F| ~ 0.04 and |U|/2 ~ 0.008 from particles whose sums are
// ~10 to ~1e3 (1e-5 relative or more). A close approach after a move cannot hide a missing pair
// elsewhere, as it would with a norm over all particles. Mixed precision takes each pair's separation
// and term in float: their rounding, up to 3.1e-6 of the sum on an H200 (cells 3 wide) and 6e-7 where
// the separations are taken in double (the largest skin), stays under a missing pair's 1e-5.
double tolerance() { return g_precision == "double" ? 1e-10 : 5e-6; }

double force_deviation(const std::vector<double>& forces, const PairReference& reference) {
    double worst = 0.0;
    for (std::size_t i = 0; i < reference.force_scale.size(); ++i) {
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) d2 += std::pow(forces[3 * i + k] - reference.forces[3 * i + k], 2);
        worst = std::max(worst, std::sqrt(d2) / std::max(reference.force_scale[i], 1e-300));
    }
    return worst;
}

double energy_deviation(const std::vector<double>& energies, const PairReference& reference) {
    double worst = 0.0;
    for (std::size_t i = 0; i < energies.size(); ++i)
        worst = std::max(worst, std::abs(energies[i] - reference.energies[i]) /
                                    std::max(reference.energy_scale[i], 1e-300));
    return worst;
}

struct SkinCase {
    std::string name;
    double verlet_factor;
    double skin() const { return kCutoff * (verlet_factor - 1.0); }
    double list_radius() const { return kCutoff * verlet_factor; }
};

class ListHalfSkin : public ::testing::TestWithParam<SkinCase> {
protected:
    void SetUp() override {
        const Vec3 box{kBoxLength, kBoxLength, kBoxLength};
        m_positions = random_positions(box, static_cast<std::size_t>(kDensity * std::pow(kBoxLength, 3)), kMinDistance, 91);
        SystemSpec spec;
        spec.box = box;
        spec.positions = m_positions;
        spec.velocities.assign(m_positions.size(), Vec3{0.0, 0.0, 0.0});
        spec.mass = kHeavyMass;
        spec.force_field = lennard_jones_force_field(1.0, kCutoff, GetParam().verlet_factor, false);
        spec.integrator = velocity_verlet(kTimeStep);
        m_sim = load_document(input_document(spec), g_backend, g_precision);
        ASSERT_TRUE(m_sim);
        read_array(m_sim.get(), structmd_get_forces);  // builds the list at these positions
        ASSERT_EQ(read_counters(m_sim.get())["neighbour_list_builds"], 1);
    }

    Vec3 separation(std::size_t i, std::size_t j) const {
        Vec3 d;
        for (int k = 0; k < 3; ++k) d[k] = minimum_image(m_positions[j][k] - m_positions[i][k], kBoxLength);
        return d;
    }

    // Disjoint pairs whose separation lies in [low, high).
    std::vector<std::pair<std::size_t, std::size_t>> pairs_between(double low, double high) const {
        std::vector<bool> taken(m_positions.size(), false);
        std::vector<std::pair<std::size_t, std::size_t>> pairs;
        for (std::size_t i = 0; i < m_positions.size(); ++i)
            for (std::size_t j = i + 1; j < m_positions.size() && !taken[i]; ++j) {
                const Vec3 d = separation(i, j);
                const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                if (taken[j] || r < low || r >= high) continue;
                pairs.emplace_back(i, j);
                taken[i] = taken[j] = true;
            }
        return pairs;
    }

    // Velocities that bring each pair closer by 2 x `each` along its separation within `steps` steps;
    // every other particle stays.
    std::vector<double> approach_velocities(const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                                            double each, int steps) const {
        std::vector<double> v(3 * m_positions.size(), 0.0);
        const double speed = each / (steps * kTimeStep);
        for (const auto& [i, j] : pairs) {
            const Vec3 d = separation(i, j);
            const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (int k = 0; k < 3; ++k) {
                v[3 * i + k] = speed * d[k] / r;
                v[3 * j + k] = -speed * d[k] / r;
            }
        }
        return v;
    }

    // Steps with the given velocities, then compares forces and per-particle energies with the
    // all-pairs reference at the positions reached; returns how many of `pairs` ended within the
    // cutoff, the pairs that a stale list would miss.
    int step_and_compare(const std::vector<double>& velocities, int steps,
                         const std::vector<std::pair<std::size_t, std::size_t>>& pairs) {
        const std::int64_t n = particle_count(m_sim.get());
        EXPECT_EQ(structmd_set_velocities(m_sim.get(), velocities.data(), n), STRUCTMD_OK)
            << structmd_last_error(m_sim.get());
        EXPECT_EQ(structmd_step(m_sim.get(), steps), STRUCTMD_OK) << structmd_last_error(m_sim.get());
        const std::vector<double> xyz = read_array(m_sim.get(), structmd_get_positions);
        const PairReference reference = all_pairs_lennard_jones(xyz, {kBoxLength, kBoxLength, kBoxLength}, 1.0, kCutoff, false);
        const double forces = force_deviation(read_array(m_sim.get(), structmd_get_forces), reference);
        const double energies = energy_deviation(read_array(m_sim.get(), structmd_get_particle_energies, 1), reference);
        int within = 0;
        for (const auto& [i, j] : pairs) {
            double r2 = 0.0;
            for (int k = 0; k < 3; ++k) r2 += std::pow(minimum_image(xyz[3 * j + k] - xyz[3 * i + k], kBoxLength), 2);
            within += r2 < kCutoff * kCutoff;
        }
        std::printf("[ deviation ] skin %.3f: forces %.2e, energies %.2e; %d of %zu moved pairs within the cutoff\n",
                    GetParam().skin(), forces, energies, within, pairs.size());
        EXPECT_LT(forces, tolerance());
        EXPECT_LT(energies, tolerance());
        return within;
    }

    std::int64_t builds() { return read_counters(m_sim.get())["neighbour_list_builds"].get<std::int64_t>(); }

    std::vector<Vec3> m_positions;
    SimHandle m_sim;
};

// Pairs at r in [r_c + 0.9 skin, r_c + 0.98 skin), inside the list radius, end 0.98 skin closer: just
// inside the cutoff, with no rebuild due. A list built with a shorter radius than r_c + skin misses them.
TEST_P(ListHalfSkin, PairsApproachingByJustUnderHalfTheSkinEachAreFound) {
    const double skin = GetParam().skin();
    const auto pairs = pairs_between(kCutoff + 0.9 * skin, kCutoff + 0.98 * skin);
    const int within = step_and_compare(approach_velocities(pairs, 0.49 * skin, 1), 1, pairs);
    EXPECT_GE(within, 10) << "too few pairs crossed into the cutoff to test anything";
    EXPECT_EQ(builds(), 1) << "moves under half the skin rebuilt the list: the stale list went untested";
}

// Every particle moved by 0.45 to 0.499 of the skin in a random direction, in one step.
TEST_P(ListHalfSkin, RandomMovesOfJustUnderHalfTheSkinMissNoPair) {
    const double skin = GetParam().skin();
    SplitMix64 rng(93);
    std::vector<double> v(3 * m_positions.size());
    for (std::size_t i = 0; i < m_positions.size(); ++i) {
        const Vec3 direction{rng.normal(), rng.normal(), rng.normal()};
        const double norm = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
        const double length = rng.uniform(0.45, 0.499) * skin;
        for (int k = 0; k < 3; ++k) v[3 * i + k] = length * direction[k] / (norm * kTimeStep);
    }
    step_and_compare(v, 1, {});
    EXPECT_EQ(builds(), 1) << "moves under half the skin rebuilt the list: the stale list went untested";
}

// Pairs just outside the list radius, [r_list, r_list + 0.02 skin), approach by 0.51 of the skin each,
// in one step or in five: they end just inside the cutoff and are found only if the list is rebuilt
// once some particle has moved more than half the skin since the last build (not within one step).
TEST_P(ListHalfSkin, PairsApproachingByJustOverHalfTheSkinEachAreFound) {
    const double skin = GetParam().skin();
    const auto pairs = pairs_between(GetParam().list_radius(), GetParam().list_radius() + 0.02 * skin);
    for (int steps : {1, 5}) {
        SCOPED_TRACE(std::to_string(steps) + " steps");
        const std::int64_t builds_before = builds();
        const int within = step_and_compare(approach_velocities(pairs, 0.51 * skin, steps), steps, pairs);
        EXPECT_GE(within, 1) << "no pair crossed into the cutoff: the case tests nothing";
        EXPECT_GT(builds(), builds_before) << "moves over half the skin did not rebuild the list";
        // Move the pairs back apart, so the second round starts from the same separations.
        std::vector<double> back = approach_velocities(pairs, -0.51 * skin, steps);
        EXPECT_EQ(structmd_set_velocities(m_sim.get(), back.data(), static_cast<std::int64_t>(m_positions.size())),
                  STRUCTMD_OK);
        EXPECT_EQ(structmd_step(m_sim.get(), steps), STRUCTMD_OK) << structmd_last_error(m_sim.get());
    }
}

INSTANTIATE_TEST_SUITE_P(Skins, ListHalfSkin,
                         ::testing::Values(SkinCase{"Skin0p1", 1.04}, SkinCase{"Skin0p3", 1.12},
                                           SkinCase{"Skin0p75", 1.3}),
                         [](const ::testing::TestParamInfo<SkinCase>& info) { return info.param.name; });

}  // namespace
}  // namespace structmd_stability

int main(int argc, char** argv) {
    for (int k = 1; k < argc; ++k)
        if (std::strncmp(argv[k], "--precision=", 12) == 0) structmd_stability::g_precision = argv[k] + 12;
    return structmd_stability::run_tests_on_backend(argc, argv, structmd_stability::g_backend,
                                                    structmd_stability::g_precision);
}
