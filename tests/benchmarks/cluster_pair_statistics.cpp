// How much work cluster pairs (neighbour/cluster_view.hpp) give the pair kernel on the benchmarks' LJ
// liquid (fcc at density 0.8442, jittered by up to 0.15 sigma, rc 2.5, list radius 2.8), against
// per-particle lists: particles per cluster, partners per cluster, the pair evaluations per particle
// that the cluster kernel makes (16 per partner, shared by the cluster's particles), the entries of
// a per-particle list, and the pairs within the cutoff. The CPU backend builds both lists, so the
// figures need no GPU.
//
//   structmd_cluster_pair_statistics [fcc cells per box edge ...]   (default 20 and 40: 32,000 and 256,000)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "neighbour/verlet_list.hpp"

namespace {

using namespace structmd;

void report(int cells) {
    CpuBackend backend(0);
    const double a = std::cbrt(4.0 / 0.8442), length = a * cells;
    const Box<double> box = Box<double>::make(length, length, length);
    const int64_t n = 4LL * cells * cells * cells;
    HostBuffer<Real4<double>> pos;
    backend.resize(pos, n);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> jitter(-0.15, 0.15);
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    int64_t k = 0;
    for (int x = 0; x < cells; ++x)
        for (int y = 0; y < cells; ++y)
            for (int z = 0; z < cells; ++z)
                for (const auto& b : basis) {
                    const Vec3<double> r = box.wrap({(x + b[0]) * a + jitter(rng), (y + b[1]) * a + jitter(rng),
                                                     (z + b[2]) * a + jitter(rng)});
                    pos.data()[k++] = {r.x, r.y, r.z, 0.0};
                }
    VerletList<CpuBackend, double> list(backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr, true);
    list.update(pos, n, box, 1);
    const ClusterView<double> v = list.cluster_view();
    int64_t partners = 0, used = 0, within = 0;
    for (int c = 0; c < v.clusters; ++c) {
        if (v.bounds[2 * c] == v.bounds[2 * c + 1]) continue;
        ++used;
        partners += v.count[c];
        v.for_each_partner(c, 0, 1, [&](int first, int end) {
            for (int s = v.bounds[2 * c]; s < v.bounds[2 * c + 1]; ++s)
                for (int t = first; t < end; ++t) {
                    const Vec3<double> d = box.minimum_image(xyz(v.positions[t]) - xyz(v.positions[s]));
                    within += t != s && dot(d, d) < 2.5 * 2.5;
                }
        });
    }
    list.view();  // asks for the per-particle lists: the next update builds them too
    list.invalidate();
    list.update(pos, n, box, 2);
    const NeighbourView<double> particles = list.view();
    int64_t listed = 0;
    for (int64_t s = 0; s < n; ++s) listed += particles.count[s];
    std::printf("%10lld  %12.2f  %12.1f  %14.1f  %14.1f  %14.1f\n", static_cast<long long>(n),
                static_cast<double>(n) / used, static_cast<double>(partners) / used,
                static_cast<double>(partners) * kClusterSize * kClusterSize / n, static_cast<double>(listed) / n,
                static_cast<double>(within) / n);
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<int> sizes;
    for (int k = 1; k < argc; ++k) sizes.push_back(std::atoi(argv[k]));
    if (sizes.empty()) sizes = {20, 40};
    std::printf("%10s  %12s  %12s  %14s  %14s  %14s\n", "N", "per cluster", "partners", "cluster pairs", "list entries",
                "within rc");
    for (const int cells : sizes) report(cells);
}
