#include "simulation/host_transfer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/box.hpp"
#include "core/error.hpp"
#include "core/random.hpp"

namespace structmd {

template <class R>
void pack_positions_of(const double* xyz, const int64_t* ids, int64_t m, const std::array<double, 3>& lengths,
                       const std::vector<int32_t>& types, Real4<R>* positions, Image* images) {
    const Box<double> box = Box<double>::make(lengths[0], lengths[1], lengths[2]);
    for (int64_t k = 0; k < m; ++k) {
        const int64_t id = ids ? ids[k] : k;
        for (int d = 0; d < 3; ++d) {
            const double x = xyz[3 * k + d];
            if (!std::isfinite(x) || std::fabs(x) > 1e8 * lengths[d]) {
                char text[32];
                std::snprintf(text, sizeof text, "%.17g", x);
                throw Error(STRUCTMD_ERR_ARGUMENT, "position of particle id " + std::to_string(id) + ": coordinate " +
                                                       std::to_string(d) + " is " + text +
                                                       ": expected a finite value within 1e8 box lengths of the box");
            }
        }
        images[k] = Image{0, 0, 0};
        const Vec3<double> r = box.wrap({xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]}, images[k]);
        positions[k] = {R(r.x), R(r.y), R(r.z), R(types[id])};
    }
}

template <class R>
void pack_velocities_of(const double* v, const int64_t* ids, int64_t m, const std::vector<double>& masses,
                        Real4<R>* velocities) {
    for (int64_t k = 0; k < m; ++k)
        velocities[k] = {R(v[3 * k]), R(v[3 * k + 1]), R(v[3 * k + 2]), R(masses[ids ? ids[k] : k])};
}

template <class R>
void unpack_vectors(const Real4<R>* values, int64_t m, double* xyz) {
    for (int64_t i = 0; i < m; ++i) {
        xyz[3 * i] = values[i].x;
        xyz[3 * i + 1] = values[i].y;
        xyz[3 * i + 2] = values[i].z;
    }
}

template void pack_positions_of<float>(const double*, const int64_t*, int64_t, const std::array<double, 3>&,
                                       const std::vector<int32_t>&, Real4<float>*, Image*);
template void pack_positions_of<double>(const double*, const int64_t*, int64_t, const std::array<double, 3>&,
                                        const std::vector<int32_t>&, Real4<double>*, Image*);
template void pack_velocities_of<float>(const double*, const int64_t*, int64_t, const std::vector<double>&,
                                        Real4<float>*);
template void pack_velocities_of<double>(const double*, const int64_t*, int64_t, const std::vector<double>&,
                                         Real4<double>*);
template void unpack_vectors<float>(const Real4<float>*, int64_t, double*);
template void unpack_vectors<double>(const Real4<double>*, int64_t, double*);

std::vector<double> maxwell_boltzmann(const SimulationSpec& spec) {
    const int64_t n = static_cast<int64_t>(spec.positions.size());
    std::vector<double> v(3 * n);
    // Each batch is a system of its own: its centre-of-mass momentum is removed on its own, which
    // also keeps the draw of a batch the same whichever share of the batches an engine holds.
    std::vector<int32_t> batches(spec.batchId.begin(), spec.batchId.end());
    std::sort(batches.begin(), batches.end());
    batches.erase(std::unique(batches.begin(), batches.end()), batches.end());
    auto batch_of = [&](int64_t i) {
        if (spec.batchId.empty()) return size_t{0};
        return static_cast<size_t>(std::lower_bound(batches.begin(), batches.end(), spec.batchId[i]) - batches.begin());
    };
    const size_t count = std::max<size_t>(batches.size(), 1);
    std::vector<std::array<double, 3>> momentum(count, {0.0, 0.0, 0.0});
    std::vector<double> totalMass(count, 0.0);
    std::vector<int64_t> members(count, 0);
    for (int64_t i = 0; i < n; ++i) {
        double normal[4];
        normal4(spec.seed, static_cast<uint64_t>(i + spec.firstParticleId), 0, normal);
        const size_t b = batch_of(i);
        ++members[b];
        // A massless particle (a type of mass 0, as Brownian inputs write) has no thermal velocity.
        if (!(spec.mass[i] > 0.0)) continue;
        const double sigma = std::sqrt(spec.velocityKT / spec.mass[i]);
        for (int d = 0; d < 3; ++d) {
            v[3 * i + d] = sigma * normal[d];
            momentum[b][d] += spec.mass[i] * v[3 * i + d];
        }
        totalMass[b] += spec.mass[i];
    }
    for (int64_t i = 0; i < n; ++i) {
        const size_t b = batch_of(i);
        if (members[b] > 1 && totalMass[b] > 0.0 && spec.mass[i] > 0.0)
            for (int d = 0; d < 3; ++d) v[3 * i + d] -= momentum[b][d] / totalMass[b];
    }
    return v;
}

std::vector<double> flatten(const std::vector<std::array<double, 3>>& vectors) {
    std::vector<double> flat;
    flat.reserve(3 * vectors.size());
    for (const auto& v : vectors) flat.insert(flat.end(), v.begin(), v.end());
    return flat;
}

}  // namespace structmd
