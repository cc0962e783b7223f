#pragma once
// The reciprocal part of the Ewald sum of ["LongRange","Electrostatics"] by smooth particle-mesh
// Ewald (Essmann et al., J. Chem. Phys. 103, 8577 (1995)): charges spread on a grid with cardinal
// B-splines, one forward FFT, the influence function, one inverse FFT, and each particle's potential
// and its gradient read back through the same B-splines. Forces are the exact gradient of the mesh
// energy (analytical differentiation of the B-splines), so energy and forces agree to rounding.
//
// The FFT is the backend's (B::Fft3d, core/fft_grid.hpp). Spreading gives each grid line along x
// to one thread, which sums the charges whose splines reach it from the particles binned by the
// line of their spline base (neighbour/line_bins.hpp): no atomics on the mesh, and each charge is
// read by the 36 lines it reaches, not by every thread.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/atomic.hpp"
#include "core/error.hpp"
#include "core/fft_grid.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/interactor.hpp"
#include "neighbour/line_bins.hpp"
#include "state/particles.hpp"

namespace structmd {

// The order of the B-splines: even, so that no wave number of the grid loses its interpolation
// factor (odd orders vanish at the Nyquist frequency).
constexpr int kPmeOrder = 6;

// Everything the mesh needs, fixed when the input is read (electrostatics_read.cpp).
struct PmePlan {
    FftGrid grid;
    double box[3] = {0, 0, 0};
    double prefactor = 0.0;       // k_e = f / eps_r
    double farWidth = 0.0;        // s: the width of the Gaussians the mesh carries
    double selfEnergy = 0.0;      // per q^2: the mesh's interaction of a charge with itself, removed
    double backgroundEnergy = 0.0;  // per q: a particle's share of the neutralising background
    double totalCharge = 0.0;
};

// floor(u) folded into [0, K): the grid point at or below grid coordinate u.
template <class R>
SMD_HD SMD_INLINE int spline_base(R u, int K) {
    const int below = static_cast<int>(floor(u)) % K;
    return below < 0 ? below + K : below;
}

// The B-spline weights of the grid points u0 - j (j < kPmeOrder) for a particle at grid coordinate
// u, u0 = floor(u), and their derivatives along u: w[j] = M_p(t + j), t = u - u0.
template <class R>
struct BSplineWeights {
    R w[kPmeOrder];
    R dw[kPmeOrder];
    int base;  // u0, folded into [0, K)

    SMD_HD SMD_INLINE BSplineWeights(R u, int K) {
        const R t = u - floor(u);
        base = spline_base(u, K);
        for (int j = 0; j < kPmeOrder; ++j) w[j] = R(0);
        w[0] = t;  // M_2(t), M_2(t + 1)
        w[1] = R(1) - t;
        for (int n = 3; n <= kPmeOrder; ++n) {
            if (n == kPmeOrder)  // dM_p(x)/dx = M_{p-1}(x) - M_{p-1}(x - 1)
                for (int j = 0; j < kPmeOrder; ++j) dw[j] = w[j] - (j > 0 ? w[j - 1] : R(0));
            // M_n(x) = [x M_{n-1}(x) + (n - x) M_{n-1}(x - 1)] / (n - 1), highest j first (in place)
            for (int j = n - 1; j >= 0; --j)
                w[j] = ((t + R(j)) * w[j] + (R(n) - t - R(j)) * (j > 0 ? w[j - 1] : R(0))) / R(n - 1);
        }
    }
};

template <class R>
SMD_HD SMD_INLINE R grid_coordinate(R x, R inverseLength, int K) {
    return R(K) * (x * inverseLength + R(0.5));
}

SMD_HD SMD_INLINE int fold_index(int i, int K) { return i < 0 ? i + K : i; }

// The grid line (y, z) of a charged group member's spline base (-1 for a particle that spreads
// nothing), by which LineBins sorts the particles.
template <class R>
struct PmeChargeLine {
    const Real4<R>* pos;
    const R* charge;
    const uint8_t* group;
    Box<R> box;
    FftGrid grid;

    SMD_HD int operator()(int64_t i) const {
        if (charge[i] == R(0) || (group && !group[i])) return -1;
        const Real4<R> r = pos[i];
        const int y = spline_base(grid_coordinate(r.y, box.inverse.y, grid.ny), grid.ny);
        const int z = spline_base(grid_coordinate(r.z, box.inverse.z, grid.nz), grid.nz);
        return z * grid.ny + y;
    }
};

// One grid line along x, cleared and then summed: a charge whose spline base lies on line
// (y + b, z + c) adds q w_y[b] w_z[c] w_x[a] at x = base_x - a. Bins are read in (c, b) order and
// each in particle order, so the sum does not depend on thread timing.
template <class R>
struct PmeSpreadLine {
    const Real4<R>* pos;
    const R* charge;
    const int* order;
    const int* lineStart;
    Box<R> box;
    FftGrid grid;
    R* mesh;

    SMD_HD void operator()(int64_t line) const {
        const int y = static_cast<int>(line % grid.ny), z = static_cast<int>(line / grid.ny);
        R* row = mesh + grid.index(0, y, z);
        for (int x = 0; x < grid.nx; ++x) row[x] = R(0);
        for (int c = 0; c < kPmeOrder; ++c) {
            const int binZ = (z + c) % grid.nz;
            for (int b = 0; b < kPmeOrder; ++b) {
                const int bin = binZ * grid.ny + (y + b) % grid.ny;
                for (int s = lineStart[bin]; s < lineStart[bin + 1]; ++s) {
                    const int i = order[s];
                    const Real4<R> r = pos[i];
                    const BSplineWeights<R> wx(grid_coordinate(r.x, box.inverse.x, grid.nx), grid.nx);
                    const BSplineWeights<R> wy(grid_coordinate(r.y, box.inverse.y, grid.ny), grid.ny);
                    const BSplineWeights<R> wz(grid_coordinate(r.z, box.inverse.z, grid.nz), grid.nz);
                    const R qyz = charge[i] * wy.w[b] * wz.w[c];
                    for (int a = 0; a < kPmeOrder; ++a) row[fold_index(wx.base - a, grid.nx)] += qyz * wx.w[a];
                }
            }
        }
    }
};

// The spectrum times the influence function (real: the transform of a symmetric kernel).
template <class R>
struct PmeConvolve {
    Complex<R>* spectrum;
    const R* influence;

    SMD_HD void operator()(int64_t k) const {
        spectrum[k].re *= influence[k];
        spectrum[k].im *= influence[k];
    }
};

// Each particle's potential phi (the grid of potentials read through its splines) and its gradient:
// F = -q grad phi, and the energy q phi / 2 less the self and background terms.
template <class R, bool WantForce, bool WantEnergy>
struct PmeGather {
    const Real4<R>* pos;
    const R* charge;
    const uint8_t* group;
    Box<R> box;
    FftGrid grid;
    const R* potential;
    R selfEnergy, backgroundEnergy;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        const R q = charge[i];
        if (q == R(0) || (group && !group[i])) return;
        const Real4<R> r = pos[i];
        const BSplineWeights<R> wx(grid_coordinate(r.x, box.inverse.x, grid.nx), grid.nx);
        const BSplineWeights<R> wy(grid_coordinate(r.y, box.inverse.y, grid.ny), grid.ny);
        const BSplineWeights<R> wz(grid_coordinate(r.z, box.inverse.z, grid.nz), grid.nz);
        R phi = R(0);
        Vec3<R> grad{R(0), R(0), R(0)};  // along the grid coordinates
        for (int c = 0; c < kPmeOrder; ++c) {
            const int z = fold_index(wz.base - c, grid.nz);
            for (int b = 0; b < kPmeOrder; ++b) {
                const R* line = potential + grid.index(0, fold_index(wy.base - b, grid.ny), z);
                R sum = R(0), sumdx = R(0);
                for (int a = 0; a < kPmeOrder; ++a) {
                    const R g = line[fold_index(wx.base - a, grid.nx)];
                    sum += wx.w[a] * g;
                    sumdx += wx.dw[a] * g;
                }
                phi += wz.w[c] * wy.w[b] * sum;
                grad.x += wz.w[c] * wy.w[b] * sumdx;
                grad.y += wz.w[c] * wy.dw[b] * sum;
                grad.z += wz.dw[c] * wy.w[b] * sum;
            }
        }
        const Vec3<R> f{-q * grad.x * R(grid.nx) * box.inverse.x, -q * grad.y * R(grid.ny) * box.inverse.y,
                        -q * grad.z * R(grid.nz) * box.inverse.z};
        const R e = R(0.5) * q * phi - selfEnergy * q * q - backgroundEnergy * q;
        add_to_outputs<WantForce, WantEnergy, false>(out, i, f, e, zero_tensor<R>());
    }
};

// The virial of one wave vector of the half spectrum (the convolution not yet applied): its energy
// E_k = G(k) |Q(k)|^2 / 2, twice for the columns that stand for k and -k, times
// delta_ab - 2 (s^2 + 1/k^2) k_a k_b, the derivative of the mesh energy under a strain of the box.
template <class R>
struct PmeWaveVirial {
    const Complex<R>* spectrum;
    const R* influence;
    FftGrid grid;
    Vec3<R> length;
    R farWidth2;

    SMD_HD Tensor3<R> operator()(int64_t at) const {
        const int hx = grid.half_x();
        const int x = static_cast<int>(at % hx);
        const int y = static_cast<int>((at / hx) % grid.ny);
        const int z = static_cast<int>(at / (int64_t(hx) * grid.ny));
        const R twoPi = R(6.283185307179586);
        const Vec3<R> k{twoPi * R(x) / length.x, twoPi * R(y <= grid.ny / 2 ? y : y - grid.ny) / length.y,
                        twoPi * R(z <= grid.nz / 2 ? z : z - grid.nz) / length.z};
        const R k2 = dot(k, k);
        if (!(k2 > R(0))) return zero_tensor<R>();
        const bool paired = x > 0 && 2 * x != grid.nx;  // -k is not stored: it counts through k
        const R energy = (paired ? R(1) : R(0.5)) * influence[at] *
                         (spectrum[at].re * spectrum[at].re + spectrum[at].im * spectrum[at].im);
        Tensor3<R> w = (R(-2) * energy * (farWidth2 + R(1) / k2)) * outer(k, k);
        w.xx += energy;
        w.yy += energy;
        w.zz += energy;
        return w;
    }
};

// Whether particle i takes part (charged, and in the group): counted to share the virial out.
template <class R>
struct PmeCharged {
    const R* charge;
    const uint8_t* group;
    SMD_HD int64_t operator()(int64_t i) const { return charge[i] != R(0) && (!group || group[i]) ? 1 : 0; }
};

// Adds a share of the mesh's virial (a property of the box, not of one particle) to each charged
// particle: the sum is exact, the split between particles a convention.
template <class R>
struct PmeShareVirial {
    const R* charge;
    const uint8_t* group;
    Tensor3<R> share;
    Tensor3<R>* virial;
    SMD_HD void operator()(int64_t i) const {
        if (charge[i] != R(0) && (!group || group[i])) virial[i] += share;
    }
};

#if SMD_HOST_CODE
// The influence function on the half spectrum: 4 pi k_e B(m) exp(-k^2 s^2) / (V k^2), B the
// B-splines' interpolation factor, 0 at k = 0 (the neutralising background).
inline std::vector<double> pme_influence(const PmePlan& plan) {
    const FftGrid& g = plan.grid;
    const int sizes[3] = {g.nx, g.ny, g.nz};
    std::vector<double> factor[3];  // B along each axis, by index
    for (int d = 0; d < 3; ++d) {
        const int K = sizes[d];
        const BSplineWeights<double> atNodes(0.0, K);  // w[j] = M_p(j)
        factor[d].resize(K);
        for (int m = 0; m < K; ++m) {
            double re = 0.0, im = 0.0;
            for (int j = 0; j + 1 < kPmeOrder; ++j) {
                const double angle = 2.0 * M_PI * m * j / K;
                re += atNodes.w[j + 1] * std::cos(angle);
                im += atNodes.w[j + 1] * std::sin(angle);
            }
            factor[d][m] = 1.0 / (re * re + im * im);
        }
    }
    const double volume = plan.box[0] * plan.box[1] * plan.box[2];
    const double s2 = plan.farWidth * plan.farWidth;
    const auto wave = [&](int m, int d) {
        const int folded = m <= sizes[d] / 2 ? m : m - sizes[d];
        return 2.0 * M_PI * folded / plan.box[d];
    };
    std::vector<double> influence(static_cast<size_t>(g.spectrum_points()));
    for (int z = 0; z < g.nz; ++z)
        for (int y = 0; y < g.ny; ++y)
            for (int x = 0; x < g.half_x(); ++x) {
                const double kx = wave(x, 0), ky = wave(y, 1), kz = wave(z, 2);
                const double k2 = kx * kx + ky * ky + kz * kz;
                const size_t at = x + size_t(g.half_x()) * (y + size_t(g.ny) * z);
                influence[at] = k2 > 0.0 ? 4.0 * M_PI * plan.prefactor * factor[0][x] * factor[1][y] * factor[2][z] *
                                               std::exp(-k2 * s2) / (volume * k2)
                                         : 0.0;
            }
    return influence;
}

template <class B, class R>
class PmeMesh {
public:
    PmeMesh(const B& backend, const PmePlan& plan)
        : backend_(backend), plan_(plan), fft_(backend, plan.grid), bins_(backend, plan.grid.ny * plan.grid.nz) {
        const std::vector<double> influence = pme_influence(plan);
        const std::vector<R> values(influence.begin(), influence.end());
        backend_.upload(influence_, values.data(), values.size());
        backend_.resize(mesh_, static_cast<size_t>(plan.grid.points()));
        backend_.resize(spectrum_, static_cast<size_t>(plan.grid.spectrum_points()));
    }

    void compute(Particles<B, R>& p, const uint8_t* group, const ForceOutputs<R>& out, const std::string& name) {
        for (int d = 0; d < 3; ++d)
            if (static_cast<double>((&p.box.length.x)[d]) != static_cast<double>(R(plan_.box[d])))
                throw Error(STRUCTMD_ERR_UNSUPPORTED,
                            name + ": the box changed since the input was read; the mesh of [\"LongRange\", "
                                   "\"Electrostatics\"] is made for the box it was read with");
        const FftGrid grid = plan_.grid;
        spread(p, group);
        fft_.forward(mesh_.data(), spectrum_.data());
        if (out.virial) add_virial(p, group, out.virial);
        backend_.for_each(grid.spectrum_points(), PmeConvolve<R>{spectrum_.data(), influence_.data()});
        fft_.inverse(spectrum_.data(), mesh_.data());
        dispatch_outputs(out, [&](auto force, auto energy, auto) {
            if constexpr (decltype(force)::value || decltype(energy)::value)
                backend_.for_each(p.count, PmeGather<R, decltype(force)::value, decltype(energy)::value>{
                                               p.pos.data(), p.charge.data(), group, p.box, grid, mesh_.data(),
                                               R(plan_.selfEnergy), R(plan_.backgroundEnergy), out});
        });
    }

private:
    // The charges onto mesh_: binned by grid line, then one thread a line.
    void spread(Particles<B, R>& p, const uint8_t* group) {
        const FftGrid grid = plan_.grid;
        bins_.sort(p.count, PmeChargeLine<R>{p.pos.data(), p.charge.data(), group, p.box, grid});
        backend_.for_each(grid.ny * grid.nz, PmeSpreadLine<R>{p.pos.data(), p.charge.data(), bins_.order(),
                                                              bins_.line_start(), p.box, grid, mesh_.data()});
    }

    void add_virial(Particles<B, R>& p, const uint8_t* group, Tensor3<R>* virial) {
        const int64_t charged = backend_.reduce(p.count, PmeCharged<R>{p.charge.data(), group}, int64_t(0));
        if (charged == 0) return;
        Tensor3<R> total = backend_.reduce(
            plan_.grid.spectrum_points(),
            PmeWaveVirial<R>{spectrum_.data(), influence_.data(), plan_.grid, p.box.length,
                             R(plan_.farWidth * plan_.farWidth)},
            zero_tensor<R>());
        const R background = R(-plan_.backgroundEnergy * plan_.totalCharge);  // E_bg, of 1/V: its virial is E_bg
        total.xx += background;
        total.yy += background;
        total.zz += background;
        backend_.for_each(p.count, PmeShareVirial<R>{p.charge.data(), group, (R(1) / R(charged)) * total, virial});
    }

    const B& backend_;
    PmePlan plan_;
    typename B::template Fft3d<R> fft_;
    typename B::template Buffer<R> influence_;
    typename B::template Buffer<R> mesh_;  // the charges, then the potentials
    typename B::template Buffer<Complex<R>> spectrum_;
    LineBins<B> bins_;  // the charges by grid line (spread())
};
#endif

}  // namespace structmd
