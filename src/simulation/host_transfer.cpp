#include "simulation/host_transfer.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/box.hpp"
#include "core/error.hpp"
#include "core/random.hpp"

namespace structmd {

template <class R>
void pack_positions_of(const double* xyz, const int64_t* ids, int64_t m, const std::array<double, 3>& lengths,
                       const std::vector<int32_t>& types, std::vector<Real4<R>>& positions, std::vector<Image>& images) {
    const Box<double> box = Box<double>::make(lengths[0], lengths[1], lengths[2]);
    positions.resize(static_cast<size_t>(m));
    images.assign(static_cast<size_t>(m), Image{0, 0, 0});
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
        const Vec3<double> r = box.wrap({xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]}, images[k]);
        positions[k] = {R(r.x), R(r.y), R(r.z), R(types[id])};
    }
}

template <class R>
void pack_positions(const double* xyz, const std::array<double, 3>& lengths, const std::vector<int32_t>& types,
                    std::vector<Real4<R>>& positions, std::vector<Image>& images) {
    pack_positions_of<R>(xyz, nullptr, static_cast<int64_t>(types.size()), lengths, types, positions, images);
}

template <class R>
std::vector<Real4<R>> pack_velocities_of(const double* v, const int64_t* ids, int64_t m,
                                         const std::vector<double>& masses) {
    std::vector<Real4<R>> values(static_cast<size_t>(m));
    for (int64_t k = 0; k < m; ++k)
        values[k] = {R(v[3 * k]), R(v[3 * k + 1]), R(v[3 * k + 2]), R(masses[ids ? ids[k] : k])};
    return values;
}

template <class R>
std::vector<Real4<R>> pack_velocities(const double* v, const std::vector<double>& masses) {
    return pack_velocities_of<R>(v, nullptr, static_cast<int64_t>(masses.size()), masses);
}

template <class R>
void unpack_vectors(const std::vector<Real4<R>>& values, double* xyz) {
    for (size_t i = 0; i < values.size(); ++i) {
        xyz[3 * i] = values[i].x;
        xyz[3 * i + 1] = values[i].y;
        xyz[3 * i + 2] = values[i].z;
    }
}

template void pack_positions<float>(const double*, const std::array<double, 3>&, const std::vector<int32_t>&,
                                    std::vector<Real4<float>>&, std::vector<Image>&);
template void pack_positions<double>(const double*, const std::array<double, 3>&, const std::vector<int32_t>&,
                                     std::vector<Real4<double>>&, std::vector<Image>&);
template void pack_positions_of<float>(const double*, const int64_t*, int64_t, const std::array<double, 3>&,
                                       const std::vector<int32_t>&, std::vector<Real4<float>>&, std::vector<Image>&);
template void pack_positions_of<double>(const double*, const int64_t*, int64_t, const std::array<double, 3>&,
                                        const std::vector<int32_t>&, std::vector<Real4<double>>&, std::vector<Image>&);
template std::vector<Real4<float>> pack_velocities_of<float>(const double*, const int64_t*, int64_t,
                                                             const std::vector<double>&);
template std::vector<Real4<double>> pack_velocities_of<double>(const double*, const int64_t*, int64_t,
                                                               const std::vector<double>&);
template std::vector<Real4<float>> pack_velocities<float>(const double*, const std::vector<double>&);
template std::vector<Real4<double>> pack_velocities<double>(const double*, const std::vector<double>&);
template void unpack_vectors<float>(const std::vector<Real4<float>>&, double*);
template void unpack_vectors<double>(const std::vector<Real4<double>>&, double*);

std::vector<double> maxwell_boltzmann(const SimulationSpec& spec) {
    const int64_t n = static_cast<int64_t>(spec.positions.size());
    std::vector<double> v(3 * n);
    double momentum[3] = {0, 0, 0};
    double totalMass = 0;
    for (int64_t i = 0; i < n; ++i) {
        double normal[4];
        normal4(spec.seed, static_cast<uint64_t>(i), 0, normal);
        const double sigma = std::sqrt(spec.velocityKT / spec.mass[i]);
        for (int d = 0; d < 3; ++d) {
            v[3 * i + d] = sigma * normal[d];
            momentum[d] += spec.mass[i] * v[3 * i + d];
        }
        totalMass += spec.mass[i];
    }
    if (n > 1)
        for (int64_t i = 0; i < n; ++i)
            for (int d = 0; d < 3; ++d) v[3 * i + d] -= momentum[d] / totalMass;
    return v;
}

std::vector<double> flatten(const std::vector<std::array<double, 3>>& vectors) {
    std::vector<double> flat;
    flat.reserve(3 * vectors.size());
    for (const auto& v : vectors) flat.insert(flat.end(), v.begin(), v.end());
    return flat;
}

}  // namespace structmd
