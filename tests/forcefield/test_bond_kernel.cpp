// BondKernel, the traversal every bonded term of N particles runs: each particle's forces, energy
// and virial against the bonds evaluated one at a time, over a branched topology where particles
// take part in no bond, fewer bonds than N, exactly N and more than N (the kernel gathers a pair
// bond's entries two at a time, so the last round of a particle may be partial).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "forcefield/bond_interaction.hpp"
#include "forcefield/dihedral.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "forcefield/kratky_porod.hpp"

namespace structmd {
namespace {

constexpr int kParticles = 14;
const Box<double> kBox = Box<double>::make(4.0, 4.5, 5.0);

// Random positions in the box, so that some bonds cross its boundary.
std::vector<Real4<double>> random_positions() {
    std::mt19937_64 rng(33);
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    std::vector<Real4<double>> pos(kParticles);
    for (auto& p : pos) p = {unit(rng) * kBox.length.x, unit(rng) * kBox.length.y, unit(rng) * kBox.length.z, 0.0};
    return pos;
}

// Bonds of N particles (flattened): 2 N + 1 about a centre, particle 0; then bonds from particle 1
// until it is in a multiple of N plus one, more than N; a chain through particles 2 .. 12. Particle
// 13 is in none.
template <int N>
std::vector<int> branched_topology() {
    std::vector<int> members;
    for (int b = 0; b < 2 * N + 1; ++b)
        for (int m = 0; m < N; ++m) members.push_back(m == N / 2 ? 0 : 1 + (b + m) % 12);
    const auto entries_of_1 = [&] {
        int count = 0;
        for (int m : members) count += m == 1;
        return count;
    };
    for (int b = 0; entries_of_1() <= N || entries_of_1() % N != 1; ++b)
        for (int m = 0; m < N; ++m) members.push_back(m == 0 ? 1 : 2 + (3 * b + m) % 11);
    for (int first = 2; first + N <= 13; ++first)
        for (int m = 0; m < N; ++m) members.push_back(first + m);
    return members;
}

template <class Potential>
void expect_kernel_sums_each_bond_once(const std::vector<typename Potential::template Params<double>>& kinds) {
    constexpr int N = Potential::arity;
    using Params = typename Potential::template Params<double>;
    const CpuBackend backend(1);
    const std::vector<Real4<double>> pos = random_positions();
    const std::vector<int> members = branched_topology<N>();
    const int bonds = static_cast<int>(members.size()) / N;
    std::vector<Params> params;
    for (int b = 0; b < bonds; ++b) params.push_back(kinds[b % kinds.size()]);

    std::vector<int> entriesOf(kParticles, 0);
    for (int m : members) ++entriesOf[m];
    ASSERT_EQ(entriesOf[13], 0);
    ASSERT_GT(entriesOf[0], 2 * N) << "more than two rounds";
    ASSERT_EQ(entriesOf[1] % N, 1) << "a last round of one entry";
    ASSERT_GT(entriesOf[1], N);

    // Each bond alone, its share added to each of its particles in bond order.
    std::vector<Vec3<double>> force(kParticles, Vec3<double>{0, 0, 0});
    std::vector<double> energy(kParticles, 0.0);
    std::vector<Tensor3<double>> virial(kParticles, zero_tensor<double>());
    for (int b = 0; b < bonds; ++b) {
        const int* ids = members.data() + N * b;
        Vec3<double> r[N], f[N];
        r[0] = xyz(pos[ids[0]]);
        for (int m = 1; m < N; ++m) r[m] = r[m - 1] + kBox.minimum_image(xyz(pos[ids[m]]) - xyz(pos[ids[m - 1]]));
        const double e = Potential::compute(r, params[b], kBox, f);
        Tensor3<double> w = zero_tensor<double>();
        for (int m = 1; m < N; ++m) w += outer(r[m] - r[0], f[m]);
        for (int m = 0; m < N; ++m) {
            force[ids[m]] += f[m];
            energy[ids[m]] += e / N;
            virial[ids[m]] += (1.0 / N) * w;
        }
    }

    const BondIndex<CpuBackend, N> index(backend, kParticles, members);
    std::vector<Real4<double>> outForce(kParticles, Real4<double>{0, 0, 0, 0});
    std::vector<double> outEnergy(kParticles, 0.0);
    std::vector<Tensor3<double>> outVirial(kParticles, zero_tensor<double>());
    ForceOutputs<double> out;
    out.force = outForce.data();
    out.energy = outEnergy.data();
    out.virial = outVirial.data();
    const BondKernel<Potential, double, true, true, true> kernel{pos.data(), kBox, index.firstEntry.data(),
                                                                  index.entries.data(), params.data(), out};
    for (int64_t i = 0; i < kParticles; ++i) kernel(i);

    for (int i = 0; i < kParticles; ++i) {
        const double scale = 1.0 + std::sqrt(dot(force[i], force[i]));
        EXPECT_NEAR(outForce[i].x, force[i].x, 1e-12 * scale) << "particle " << i;
        EXPECT_NEAR(outForce[i].y, force[i].y, 1e-12 * scale) << "particle " << i;
        EXPECT_NEAR(outForce[i].z, force[i].z, 1e-12 * scale) << "particle " << i;
        EXPECT_NEAR(outEnergy[i], energy[i], 1e-12 * (1.0 + std::fabs(energy[i]))) << "particle " << i;
        EXPECT_NEAR(outVirial[i].xy, virial[i].xy, 1e-12 * scale) << "particle " << i;
        EXPECT_NEAR(outVirial[i].zz, virial[i].zz, 1e-12 * scale) << "particle " << i;
    }
    EXPECT_EQ(outEnergy[13], 0.0);
    EXPECT_NE(outEnergy[0], 0.0);
}

TEST(BondKernel, SumsEachBondOnceForTwoParticles) {
    expect_kernel_sums_each_bond_once<RadialBond<HarmonicBond>>({{100.0, 1.0}, {60.0, 1.3}});
}

TEST(BondKernel, SumsEachBondOnceForThreeParticles) { expect_kernel_sums_each_bond_once<KratkyPorod>({{2.0}, {3.5}}); }

TEST(BondKernel, SumsEachBondOnceForFourParticles) {
    expect_kernel_sums_each_bond_once<Dihedral>({{1.0, 2.0, 0.3}, {3.0, 1.5, -1.0}});
}

}  // namespace
}  // namespace structmd
