// A built-in pair potential (LennardJonesType1, two types) as a transverser (forcefield/
// pair_term_transverser.hpp): over the same neighbour list it gives PairKernel's forces, energies and
// virials, and over all pairs the same again (the table's cutoff is its only reach); the forces also
// against the LJ formula summed here over every pair.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/pair_kernel.hpp"
#include "forcefield/pair_term_transverser.hpp"
#include "neighbour/verlet_list.hpp"
#include "transverser/all_pairs_traversal.hpp"
#include "transverser/neighbour_traversal.hpp"

namespace structmd {
namespace {

using LJ = LennardJonesType1;
using Params = LJ::Params<double>;

struct Outputs {
    std::vector<Real4<double>> force;
    std::vector<double> energy;
    std::vector<Tensor3<double>> virial;

    explicit Outputs(int64_t n) : force(n, Real4<double>{0, 0, 0, 0}), energy(n, 0.0), virial(n, zero_tensor<double>()) {}
    ForceOutputs<double> view() {
        ForceOutputs<double> out;
        out.force = force.data();
        out.energy = energy.data();
        out.virial = virial.data();
        return out;
    }
};

void expect_close(Outputs& a, Outputs& b, int64_t n) {
    for (int64_t i = 0; i < n; ++i) {
        const double scale = 1e-11 * (1 + std::abs(a.force[i].x) + std::abs(a.force[i].y) + std::abs(a.force[i].z));
        EXPECT_NEAR(a.force[i].x, b.force[i].x, scale) << i;
        EXPECT_NEAR(a.force[i].y, b.force[i].y, scale) << i;
        EXPECT_NEAR(a.force[i].z, b.force[i].z, scale) << i;
        EXPECT_NEAR(a.energy[i], b.energy[i], 1e-11 * (1 + std::abs(a.energy[i]))) << i;
        EXPECT_NEAR(a.virial[i].xy, b.virial[i].xy, 1e-11 * (1 + std::abs(a.virial[i].xy))) << i;
        EXPECT_NEAR(a.virial[i].zz, b.virial[i].zz, 1e-11 * (1 + std::abs(a.virial[i].zz))) << i;
    }
}

TEST(PairTermTransverser, GivesThePairKernelsForcesEnergiesAndVirials) {
    CpuBackend backend(2);
    const int64_t n = 500;
    const double length = 8.5, cutoff = 2.5;
    const Box<double> box = Box<double>::make(length, length, length);
    HostBuffer<Real4<double>> pos;
    backend.resize(pos, n);
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    // On a jittered lattice, so that no two particles are so close that the forces dwarf rounding.
    const int side = 8;
    for (int64_t i = 0; i < n; ++i) {
        const double a = length / side;
        pos.data()[i] = {(static_cast<double>(i % side) + 0.2 * u(rng)) * a - length / 2,
                         (static_cast<double>((i / side) % side) + 0.2 * u(rng)) * a - length / 2,
                         (static_cast<double>(i / (side * side)) + 0.2 * u(rng)) * a - length / 2,
                         static_cast<double>(i % 2)};
    }
    // Type pairs of their own epsilon and sigma; 1-1 shifted.
    const std::vector<Params> table = {LJ::make_pair_params<double>(1.0, 1.0, cutoff, false),
                                       LJ::make_pair_params<double>(1.5, 0.9, cutoff, false),
                                       LJ::make_pair_params<double>(1.5, 0.9, cutoff, false),
                                       LJ::make_pair_params<double>(0.7, 1.1, cutoff, true)};
    const PairTable<Params> pairs{table.data(), 2, nullptr};
    VerletList<CpuBackend, double> list(backend, cutoff, 1.2, PairCondition::all, PairFilterInputs{}, nullptr, 1,
                                        nullptr);
    list.update(pos, n, box, 1);

    Outputs kernel(n), listed(n), everything(n);
    backend.for_each_lanes(n, PairKernel<LJ, double, double, true, true, true>{nullptr, nullptr, nullptr, list.view(),
                                                                             pairs, kernel.view()});
    using Transverser = PairTermTransverser<LJ, double, double, true, true, true>;
    backend.for_each_lanes(n, NeighbourTraversal<Transverser, double>{Transverser{nullptr, nullptr, pairs, listed.view()},
                                                                      list.view(), cutoff * cutoff, nullptr});
    backend.for_each_lanes(n, AllPairsTraversal<Transverser, double>{Transverser{nullptr, nullptr, pairs, everything.view()},
                                                                     pos.data(), n, box, nullptr, nullptr});
    expect_close(kernel, listed, n);
    expect_close(kernel, everything, n);

    // The force against U = 4 eps ((s/r)^12 - (s/r)^6) (+ shift) by minimum image over every pair.
    const double eps[2][2] = {{1.0, 1.5}, {1.5, 0.7}}, sig[2][2] = {{1.0, 0.9}, {0.9, 1.1}};
    double largest = 0;
    for (int64_t i = 0; i < n; ++i) {
        Vec3<double> f{0, 0, 0};
        for (int64_t j = 0; j < n; ++j) {
            if (j == i) continue;
            const Vec3<double> d = box.minimum_image(xyz(pos.data()[j]) - xyz(pos.data()[i]));
            const double r = std::sqrt(dot(d, d));
            if (r >= cutoff) continue;
            const double e = eps[i % 2][j % 2], s = sig[i % 2][j % 2];
            const double dudr = 4 * e * (-12 * std::pow(s, 12) / std::pow(r, 13) + 6 * std::pow(s, 6) / std::pow(r, 7));
            f += (dudr / r) * d;
        }
        EXPECT_NEAR(everything.force[i].x, f.x, 1e-10 * (1 + std::abs(f.x))) << i;
        EXPECT_NEAR(everything.force[i].y, f.y, 1e-10 * (1 + std::abs(f.y))) << i;
        largest = std::max(largest, std::abs(f.x));
    }
    EXPECT_GT(largest, 0.1);  // the particles interact
}

}  // namespace
}  // namespace structmd
