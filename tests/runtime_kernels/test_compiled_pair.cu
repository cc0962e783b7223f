// A pair potential compiled at run time (NVRTC) against the same potential compiled with the
// library: Lennard-Jones written as source must give the forces, energies and virials of
// LennardJonesType1 in every precision, launched directly and replayed from a step graph. Exits
// 77 (reported as skipped) without a GPU.
#include <cuda_runtime.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "backends/cuda/cuda_backend.cuh"
#include "forcefield/compiled_interaction.hpp"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/pair_interaction.hpp"

namespace structmd {
namespace {

// LennardJonesParams' layout (epsilon, sigma^2, cutoff^2, offset), with cutoff2 where the kernel reads it.
const char* const kLennardJonesSource = R"(
struct RuntimePotential {
    template <class R> struct Params { R cutoff2; R epsilon; R sigma2; R offset; };
    template <class R> static SMD_HD PairTerm<R> evaluate(R r2, const Params<R>& p) {
        const R s2 = p.sigma2 / r2;
        const R s6 = s2 * s2 * s2;
        return {p.epsilon * R(24) * (s6 - R(2) * s6 * s6) / r2, p.epsilon * R(4) * (s6 * s6 - s6) + p.offset};
    }
};
)";

constexpr int kTypes = 2;
constexpr int64_t kParticles = 3000;
constexpr double kBox = 16.0;

struct Outputs {
    std::vector<Real4<double>> force;
    std::vector<double> energy;
    std::vector<Tensor3<double>> virial;
};

template <class R>
std::vector<Real4<R>> positions() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.5 * kBox, 0.5 * kBox);
    std::vector<Real4<R>> pos;
    // A lattice with jitter: no pair so close that float overflows.
    const int side = static_cast<int>(std::ceil(std::cbrt(double(kParticles))));
    const double a = kBox / side;
    for (int64_t i = 0; i < kParticles; ++i) {
        const int x = i % side, y = (i / side) % side, z = i / (side * side);
        pos.push_back({R(-0.5 * kBox + a * (x + 0.5) + 0.2 * a * (u(rng) / kBox)),
                       R(-0.5 * kBox + a * (y + 0.5) + 0.2 * a * (u(rng) / kBox)),
                       R(-0.5 * kBox + a * (z + 0.5) + 0.2 * a * (u(rng) / kBox)), R(i % kTypes)});
    }
    return pos;
}

template <class R, class PairR>
Outputs evaluate(bool compiled, bool inGraph) {
    CudaBackend backend(0);
    Particles<CudaBackend, R> p;
    p.count = kParticles;
    p.box = Box<R>::make(kBox, kBox, kBox);
    const std::vector<Real4<R>> pos = positions<R>();
    backend.upload(p.pos, pos.data(), pos.size());
    backend.resize(p.force, kParticles);
    backend.resize(p.energy, kParticles);
    backend.resize(p.virial, kParticles);
    backend.fill(p.force, Real4<R>{0, 0, 0, 0});
    backend.fill(p.energy, R(0));
    backend.fill(p.virial, zero_tensor<R>());

    std::vector<LennardJonesParams<PairR>> builtin;
    for (int a = 0; a < kTypes; ++a)
        for (int b = 0; b < kTypes; ++b) {
            const double sigma = 1.0 + 0.1 * (a + b), epsilon = 1.0 + 0.5 * a * b;
            builtin.push_back(LennardJonesType1::make_pair_params<PairR>(epsilon, sigma, 2.5 * sigma, true));
        }
    auto list = std::make_shared<VerletList<CudaBackend, R>>(backend, 2.5 * 1.2, 1.1, PairCondition::all,
                                                              PairFilterInputs{}, nullptr, 1, nullptr);
    std::unique_ptr<Interactor<CudaBackend, R>> term;
    if (compiled) {
        std::vector<PairR> table;
        for (const auto& q : builtin) table.insert(table.end(), {q.cutoff2, q.epsilon, q.sigma2, q.offset});
        term = std::make_unique<CompiledPairInteraction<CudaBackend, R, PairR>>(
            backend, InteractorScope{"lj"}, list, RuntimeSource{kLennardJonesSource}, table, kTypes, nullptr);
    } else {
        term = std::make_unique<PairInteraction<CudaBackend, R, LennardJonesType1, PairR>>(
            backend, InteractorScope{"lj"}, list, builtin, kTypes);
    }
    term->prepare(p);
    ForceOutputs<R> out{p.force.data(), p.energy.data(), p.virial.data()};
    if (inGraph) {
        // Two graph batches: the first builds the graph, the second replays it.
        backend.begin_steps();
        for (int step = 0; step < 32; ++step) {
            backend.begin_step();
            term->compute(p, step == 31 ? out : ForceOutputs<R>{p.force.data(), nullptr, nullptr});
        }
        backend.end_steps();
    } else {
        term->compute(p, out);
    }
    std::vector<Real4<R>> force(kParticles);
    std::vector<R> energy(kParticles);
    std::vector<Tensor3<R>> virial(kParticles);
    backend.download(p.force, force.data(), force.size());
    backend.download(p.energy, energy.data(), energy.size());
    backend.download(p.virial, virial.data(), virial.size());
    Outputs o;
    for (int64_t i = 0; i < kParticles; ++i) {
        o.force.push_back({double(force[i].x), double(force[i].y), double(force[i].z), 0.0});
        o.energy.push_back(double(energy[i]));
        const Tensor3<R>& w = virial[i];
        o.virial.push_back({double(w.xx), double(w.xy), double(w.xz), double(w.yx), double(w.yy), double(w.yz),
                            double(w.zx), double(w.zy), double(w.zz)});
    }
    return o;
}

template <class R, class PairR>
void expect_same(double tolerance, bool inGraph) {
    const Outputs a = evaluate<R, PairR>(false, inGraph), b = evaluate<R, PairR>(true, inGraph);
    double largest = 0, worst = 0;
    for (int64_t i = 0; i < kParticles; ++i) {
        const double d[] = {a.force[i].x - b.force[i].x, a.force[i].y - b.force[i].y, a.force[i].z - b.force[i].z,
                            a.energy[i] - b.energy[i], a.virial[i].xx - b.virial[i].xx, a.virial[i].yz - b.virial[i].yz};
        const double v[] = {a.force[i].x, a.force[i].y, a.force[i].z, a.energy[i], a.virial[i].xx, a.virial[i].yz};
        for (int k = 0; k < 6; ++k) {
            worst = std::max(worst, std::abs(d[k]));
            largest = std::max(largest, std::abs(v[k]));
        }
    }
    EXPECT_GT(largest, 0.1) << "the scene must have interacting pairs";
    EXPECT_LE(worst, tolerance * largest);
}

TEST(CompiledPair, MatchesTheBuiltInInDouble) { expect_same<double, double>(1e-12, false); }
TEST(CompiledPair, MatchesTheBuiltInInMixed) { expect_same<double, float>(1e-5, false); }
TEST(CompiledPair, MatchesTheBuiltInInSingle) { expect_same<float, float>(1e-5, false); }
TEST(CompiledPair, ReplaysFromAStepGraph) { expect_same<double, double>(1e-12, true); }

TEST(CompiledPair, ABadSourceIsAnInternalErrorWithTheLog) {
    CudaBackend backend(0);
    try {
        backend.compile("this is not C++", {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), STRUCTMD_ERR_INTERNAL);
        EXPECT_NE(std::string(e.what()).find("this is not C++"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace structmd

int main(int argc, char** argv) {
    int devices = 0;
    if (cudaGetDeviceCount(&devices) != cudaSuccess || devices == 0) return 77;
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
