#pragma once
// The mobility product of the doubly periodic slab (["BDHIDoublyPeriodic","DPStokes"]),
//   M v = J G S v,
// S spreading each particle's vector with the Gaussian g(r) = (2 pi sigma^2)^{-3/2} exp(-r^2 / (2 sigma^2)),
// sigma = a / sqrt(pi) (the force coupling method's: far from walls the self-mobility is 1 / (6 pi eta a)),
// onto a grid periodic in x and y and of nz uniform nodes from z = -H/2 to H/2 (the walls, where
// there are walls), 2D transforms of every z plane, the slab's Stokes solve per wave vector
// (slab_stokes.hpp), the inverse transforms, and J = S^T the Gaussian's average of the velocity at
// the particle, times the cell volume. Near a wall the Gaussian has its mirror images subtracted
// (SlabAxisZ); the part of a Gaussian beyond the slab is left out (on both sides of the product, so
// M stays symmetric). The Gaussian is cut where it falls to the integrator's tolerance of its peak
// (make_slab_plan's cut), as the force coupling method cuts its own. Only the group's particles take
// part; the product is 0 at the others.
//
// The positions are placed once (place: the Gaussians' weights are tabulated there,
// slab_spreading.hpp) and then any number of products taken (apply), as the Lanczos square root and
// the random finite difference need.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/fft_grid.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "hydrodynamics/gaussian_spreading.hpp"
#include "hydrodynamics/slab_spreading.hpp"
#include "hydrodynamics/slab_stokes.hpp"
#include "neighbour/line_bins.hpp"

namespace structmd {

// Everything the mesh needs, fixed for one box (make_slab_plan).
struct SlabPlan {
    FftGrid grid;  // nz: the z nodes, walls included
    double box[2] = {0, 0};
    double height = 0.0;  // H
    double sigma = 0.0;
    double cut = 0.0;  // the Gaussian reaches out to where it falls to cut of its peak
    int support = 0;   // points the Gaussian covers along x and y
    int supportZ = 0;
    SlabWalls walls = SlabWalls::none;
    int images = 0;  // SlabAxisZ's
};

// The Gaussian's weights along z: the `support` nodes first .. first + support - 1, first chosen
// closest to centring them on the particle but kept inside the slab. Where there are walls, the
// force density is made odd about each wall by subtracting the Gaussians of the particle's mirror
// images (UAMMD subtracts an image too): above a bottom wall the one image through it; in a slit
// the odd extension of period 2H the two walls' reflections generate, in orders m = 1, 2, ...
// (centres +-m H + (-1)^m z, signs (-1)^m: the images through either wall at +-H - z, the
// particle's copies at z +- 2H, ...), as many orders (`images`) as reach into the slab. The density
// then vanishes at each wall smoothly (a particle on a wall spreads nothing), the weights change
// smoothly with the particle's height everywhere in the slab (the image of the nearer wall alone
// would jump as the particle crosses the mid-plane), and the sum over z nodes stays as accurate as
// in the open slab.
template <class R>
struct SlabAxisZ {
    R bottom;  // -H/2
    R spacing;
    int n;
    int support;
    R inverseTwoSigma2;
    R norm;
    SlabWalls walls;
    int images;  // the slit's orders of images

    SMD_HD SMD_INLINE int first(R z) const {
        const int centred = static_cast<int>(floor((z - bottom) / spacing - R(0.5) * R(support) + R(1)));
        return centred < 0 ? 0 : (centred > n - support ? n - support : centred);
    }

    SMD_HD SMD_INLINE R weight(int node, R z) const {
        const R at = bottom + R(node) * spacing;
        R w = gaussian(at - z);
        if (walls == SlabWalls::bottom) w -= gaussian(at - (R(2) * bottom - z));
        if (walls == SlabWalls::slit)
            for (int m = 1; m <= images; ++m) {
                const R centre = m % 2 ? -z : z, shift = R(-2 * m) * bottom;
                const R pair = gaussian(at - centre - shift) + gaussian(at - centre + shift);
                w += m % 2 ? -pair : pair;
            }
        return w;
    }

private:
    SMD_HD SMD_INLINE R gaussian(R d) const { return norm * exp(-d * d * inverseTwoSigma2); }
};

template <class R>
using SlabAxes = GaussianAxes<R, SlabAxisZ<R>>;

#if SMD_HOST_CODE
// The Gaussian reaches out to where it falls to `cut` of its peak. The integrator cuts it at its
// tolerance, as the force coupling method (fcm_mesh.hpp) cuts its own: every element of M then
// stays within 0.3 tolerance mu0 of the uncut Gaussian's (measured for tolerances 1e-3 to 0.1 and
// grid spacings 0.8 to 1.9 sigma, tests/python/test_bdhi_dpstokes.py), so the tolerance needs no
// floor.
inline SlabPlan make_slab_plan(const int sizes[3], const double box[2], double height, double radius, SlabWalls walls,
                               double cut) {
    SlabPlan plan;
    plan.walls = walls;
    plan.cut = cut;
    plan.box[0] = box[0];
    plan.box[1] = box[1];
    plan.height = height;
    plan.sigma = radius / std::sqrt(M_PI);
    plan.grid = FftGrid{sizes[0], sizes[1], sizes[2]};
    const double reach = plan.sigma * std::sqrt(2.0 * std::log(1.0 / cut));
    const double finest = std::min(box[0] / sizes[0], box[1] / sizes[1]);
    plan.support = static_cast<int>(std::ceil(2.0 * reach / finest)) + 1;
    plan.supportZ = std::min(static_cast<int>(std::ceil(2.0 * reach / (height / (sizes[2] - 1)))) + 1, sizes[2]);
    // The images of order m lie at least (m - 1) H from the slab.
    plan.images = walls == SlabWalls::slit ? 1 + static_cast<int>(std::floor(reach / height)) : 0;
    return plan;
}

// The Gaussian's axes for a plan: x and y periodic, z the slab's.
template <class R>
inline SlabAxes<R> slab_axes(const SlabPlan& plan) {
    const int sizes[2] = {plan.grid.nx, plan.grid.ny};
    const R inverseTwoSigma2 = R(0.5 / (plan.sigma * plan.sigma)), norm = R(1.0 / std::sqrt(2.0 * M_PI * plan.sigma * plan.sigma));
    FcmAxis<R> axis[2];
    for (int d = 0; d < 2; ++d)
        axis[d] = FcmAxis<R>{R(plan.box[d] / sizes[d]), R(1.0 / plan.box[d]), sizes[d], plan.support, inverseTwoSigma2, norm};
    const SlabAxisZ<R> z{R(-0.5 * plan.height), R(plan.height / (plan.grid.nz - 1)), plan.grid.nz, plan.supportZ,
                         inverseTwoSigma2, norm, plan.walls, plan.images};
    return {axis[0], axis[1], z, plan.grid};
}

template <class B, class R>
class SlabMesh {
public:
    SlabMesh(const B& backend, const SlabPlan& plan)
        : backend_(backend), plan_(plan), axes_(slab_axes<R>(plan)),
          fft_(backend, FftGrid{plan.grid.nx, plan.grid.ny, 3 * plan.grid.nz}, FftAxes::xy),
          bins_(backend, plan.grid.ny * plan.grid.nz) {
        const double spacing = plan.height / (plan.grid.nz - 1);
        backend_.resize(field_, static_cast<size_t>(3 * plan.grid.points()));
        backend_.resize(spectrum_, static_cast<size_t>(3 * plan.grid.spectrum_points()));
        backend_.resize(solved_, static_cast<size_t>(3 * plan.grid.spectrum_points()));
        const int64_t waves = int64_t(plan.grid.half_x()) * plan.grid.ny;
        backend_.resize(kernel_, static_cast<size_t>(waves * plan.grid.nz));
        backend_.for_each(waves * plan.grid.nz,
                          SlabKernelTable{plan.grid, plan.box[0], plan.box[1], spacing, kernel_.data()});
    }

    const SlabPlan& plan() const { return plan_; }

    // The positions (backend memory, read here only) and group (kept by pointer until the next
    // place) of the products that follow: their Gaussians' weights are tabulated.
    void place(int64_t count, const Real4<R>* pos, const uint8_t* group) {
        count_ = count;
        group_ = group;
        backend_.resize(first_, static_cast<size_t>(3 * count));
        backend_.resize(weight_, static_cast<size_t>(weights().stride() * count));
        backend_.for_each(count, SlabWeighParticle<R, SlabAxisZ<R>>{pos, group, axes_, first_.data(), weight_.data()});
        bins_.sort(count, SlabKernelLine{group, first_.data(), plan_.grid.ny});
    }

    // out = M v, both flat (three numbers a particle) in backend memory.
    void apply(const R* v, R* out, double viscosity) {
        const FftGrid grid = plan_.grid;
        const int64_t planePoints = int64_t(grid.nx) * grid.ny;
        const int64_t planeSpectrum = int64_t(grid.half_x()) * grid.ny;
        backend_.for_each_lanes(grid.ny * grid.nz,
                                SlabSpreadLine<R, FlatVectors<R>>{{v}, bins_.order(), bins_.line_start(), weights(), grid,
                                                                  field_.data()},
                                LaneSizing::kWarp);
        fft_.forward(field_.data(), spectrum_.data());
        const double spacing = plan_.height / (grid.nz - 1);
        // A warp per wave vector at any size: the one lane that sizing by the device gives 10^6 wave
        // vectors (100,000 particles) would run under a register cap that spills the solve's doubles.
        backend_.for_each_lanes(planeSpectrum,
                                SlabStokesSolve<R>{spectrum_.data(), solved_.data(), kernel_.data(), grid, plan_.box[0],
                                                   plan_.box[1], spacing, spacing / (double(planePoints) * viscosity),
                                                   plan_.walls},
                                LaneSizing::kWarp);
        fft_.inverse(solved_.data(), field_.data());
        const double cellVolume = plan_.box[0] * plan_.box[1] * spacing / double(planePoints);
        backend_.for_each_lanes(count_, SlabInterpolate<R>{group_, weights(), grid, field_.data(), R(cellVolume), out},
                                LaneSizing::kFillDevice);
    }

private:
    SlabWeights<R> weights() const { return {first_.data(), weight_.data(), plan_.support, plan_.supportZ}; }

    const B& backend_;
    SlabPlan plan_;
    SlabAxes<R> axes_;
    typename B::template Fft3d<R> fft_;  // the 2D transforms of every z plane of the three components
    LineBins<B> bins_;
    int64_t count_ = 0;
    const uint8_t* group_ = nullptr;
    typename B::template Buffer<int> first_;  // SlabWeights'
    typename B::template Buffer<R> weight_;
    typename B::template Buffer<R> field_;  // x, y, z grids: the density, then the velocity
    typename B::template Buffer<Complex<R>> spectrum_, solved_;
    typename B::template Buffer<SlabKernelEntry> kernel_;  // SlabKernelTable's
};
#endif

}  // namespace structmd
