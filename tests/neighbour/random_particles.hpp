// Particles placed at random in a periodic box, for the neighbour-list tests: random moves of a given
// length, and every pair within a distance by an all-pairs search (the reference the lists are held to).
#pragma once

#include <cmath>
#include <random>
#include <set>
#include <utility>

#include "backends/cpu/cpu_backend.hpp"
#include "core/box.hpp"

namespace structmd {

using Pairs = std::set<std::pair<int, int>>;

struct RandomParticles {
    CpuBackend backend;
    Box<double> box;
    HostBuffer<Real4<double>> pos;
    int64_t n = 0;
    int64_t version = 0;  // every visit sees positions that may have changed

    RandomParticles(int64_t count, double lx, double ly, double lz, unsigned seed, int threads = 2)
        : backend(threads), box(Box<double>::make(lx, ly, lz)), n(count) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(-0.5, 0.5);
        backend.resize(pos, n);
        for (int64_t i = 0; i < n; ++i) pos.data()[i] = {u(rng) * lx, u(rng) * ly, u(rng) * lz, 0.0};
    }

    // Moves every particle by a random displacement of length `step` and wraps it.
    void jiggle(double step, unsigned seed) {
        std::mt19937 rng(seed);
        std::normal_distribution<double> g(0.0, 1.0);
        for (int64_t i = 0; i < n; ++i) {
            Vec3<double> d{g(rng), g(rng), g(rng)};
            d = (step / std::sqrt(dot(d, d))) * d;
            Real4<double>& p = pos.data()[i];
            const Vec3<double> r = box.wrap(xyz(p) + d);
            p = {r.x, r.y, r.z, p.w};
        }
    }

    // A liquid-like configuration in place of the random one: a cubic lattice of the given spacing
    // filling the box row by row, each site jittered by up to an eighth of it (from the random
    // positions), two types (w 0 and 1); no pair closer than about 0.75 spacings.
    void place_on_jittered_lattice(double spacing) {
        const int nx = static_cast<int>(box.length.x / spacing), ny = static_cast<int>(box.length.y / spacing);
        for (int64_t i = 0; i < n; ++i) {
            Real4<double>& p = pos.data()[i];
            const int64_t a = i % nx, b = (i / nx) % ny, c = i / (nx * ny);
            const Vec3<double> r = box.wrap({(a + 0.25 * p.x / box.length.x) * spacing,
                                             (b + 0.25 * p.y / box.length.y) * spacing,
                                             (c + 0.25 * p.z / box.length.z) * spacing});
            p = {r.x, r.y, r.z, static_cast<double>(i % 2)};
        }
    }

    // Every ordered pair (i, j), i != j, closer than cutoff.
    Pairs pairs_within(double cutoff) const {
        Pairs pairs;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const Vec3<double> d = box.minimum_image(xyz(pos.data()[j]) - xyz(pos.data()[i]));
                if (i != j && dot(d, d) < cutoff * cutoff) pairs.insert({i, j});
            }
        return pairs;
    }
};

}  // namespace structmd
