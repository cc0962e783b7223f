#pragma once
// Flat surfaces normal to z, UAMMD-structured's ["Surface", ...] family: a wall at z = z_s
// (surfacePosition, given once for the entry) with an epsilon and a sigma per particle type (a table
// of types; see external_potential.hpp). With d = z - z_s the signed distance to the wall, each acts
// on both sides, through |d|, and pushes or pulls along z only:
//   SurfaceLennardJonesTypeK      U = eps g_K(sigma/|d|)                     (the shapes of
//                                                                             lennard_jones.hpp)
//   SurfaceWCATypeK               U = eps g_K(sigma/|d|) + eps  for |d| < r_min, else 0
//   SurfaceGeneralLennardJonesTypeK   the WCA form for eps >= 0, the full form with |eps| for eps < 0
//   SurfaceIntegratedLennardJonesType2  U = eps [(sigma/|d|)^9 - 2 (sigma/|d|)^3]
//   SurfaceAnchorage              U = eps/2 [(d/sigma)^2 - 1]   for |d| <= sigma, else 0
//   ParabolaSurface               U = eps/2 d^2   for d <= 0 (below the wall), else 0  (eps only)
// F_z = -dU/dz. None of them uses the particle radius, nor the time.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "forcefield/external_potential.hpp"
#include "forcefield/lennard_jones.hpp"

namespace structmd {

// The 9-3 shape of a wall of Lennard-Jones particles integrated over a half space, in the
// parametrisation of UAMMD-structured's IntegratedLennardJones Type2: (s/r)^9 - 2 (s/r)^3. Its
// minimum is at r = (3/2)^(1/6) s with value -(4/3) sqrt(2/3) ~ -1.089 (not at s with -1, as the
// name "Type2" would suggest).
struct LennardJonesShape93 {
    template <class R>
    static SMD_HD SMD_INLINE LennardJonesShapeTerm<R> at(R sr2) {
        const R sr3 = sr2 * sqrt(sr2);
        const R sr9 = sr3 * sr3 * sr3;
        return {R(6) * sr3 - R(9) * sr9, sr9 - R(2) * sr3};
    }
};

// How a surface of the Lennard-Jones family turns a type's (eps, sigma) into the Params of
// lennard_jones.hpp, with the distance to the wall in the role of r.
enum class SurfaceForm {
    full,     // no cutoff, no offset
    wca,      // cut at the shape's minimum, lifted by eps
    general,  // wca for eps >= 0, full with |eps| for eps < 0
};

template <class Shape, SurfaceForm Form>
struct LennardJonesSurface {
    template <class R>
    struct Params {
        R position;  // z_s
        LennardJonesParams<R> lj;
    };

    static std::vector<Parameter> parameters() { return {with_default(number("surfacePosition", "length"), 0.0)}; }
    static std::vector<Parameter> type_parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)};
    }

    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return make_params<R>(v["surfacePosition"], v["epsilon"], v["sigma"]);
    }

    template <class R>
    static Params<R> make_params(double surfacePosition, double epsilon, double sigma) {
        const double sigma2 = sigma * sigma;
        if constexpr (Form != SurfaceForm::full) {
            if (Form == SurfaceForm::wca || epsilon >= 0.0) {
                const double cutoff = Shape::minimum_distance(sigma);
                return {R(surfacePosition), {R(epsilon), R(sigma2), R(cutoff * cutoff), R(epsilon)}};
            }
        }
        const double depth = Form == SurfaceForm::general ? std::fabs(epsilon) : epsilon;
        return {R(surfacePosition), {R(depth), R(sigma2), std::numeric_limits<R>::infinity(), R(0)}};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> r, R, const Params<R>& p, R, Vec3<R>& force) {
        const R d = r.z - p.position;
        const PairTerm<R> term = evaluate_lennard_jones<Shape>(d * d, p.lj);
        force = {R(0), R(0), -term.dudr_over_r * d};
        return term.energy;
    }
};

using SurfaceLennardJonesType1 = LennardJonesSurface<LennardJonesShape1, SurfaceForm::full>;
using SurfaceLennardJonesType2 = LennardJonesSurface<LennardJonesShape2, SurfaceForm::full>;
using SurfaceWCAType1 = LennardJonesSurface<LennardJonesShape1, SurfaceForm::wca>;
using SurfaceWCAType2 = LennardJonesSurface<LennardJonesShape2, SurfaceForm::wca>;
using SurfaceGeneralLennardJonesType1 = LennardJonesSurface<LennardJonesShape1, SurfaceForm::general>;
using SurfaceGeneralLennardJonesType2 = LennardJonesSurface<LennardJonesShape2, SurfaceForm::general>;
using SurfaceIntegratedLennardJonesType2 = LennardJonesSurface<LennardJonesShape93, SurfaceForm::full>;

// A harmonic well of depth eps/2 and half-width sigma centred on the wall; 0 (and no force) beyond.
// The energy is continuous at |d| = sigma, the force jumps there from -+eps/sigma to 0.
struct SurfaceAnchorage {
    template <class R>
    struct Params {
        R position;
        R epsilon;
        R sigma;
    };

    static std::vector<Parameter> parameters() { return {with_default(number("surfacePosition", "length"), 0.0)}; }
    static std::vector<Parameter> type_parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)};
    }

    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return {R(v["surfacePosition"]), R(v["epsilon"]), R(v["sigma"])};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> r, R, const Params<R>& p, R, Vec3<R>& force) {
        const R d = r.z - p.position;
        force = {R(0), R(0), R(0)};
        if (d < -p.sigma || d > p.sigma) return R(0);
        const R x = d / p.sigma;
        force.z = -p.epsilon * x / p.sigma;
        return R(0.5) * p.epsilon * (x * x - R(1));
    }
};

// A one-sided soft floor: particles below the wall are pulled back up by a spring of stiffness eps
// (energy/length^2); above it they feel nothing. Only eps is read per type; UAMMD-structured's
// generators also write a sigma column, which is accepted and ignored.
struct ParabolaSurface {
    template <class R>
    struct Params {
        R position;
        R epsilon;
    };

    static std::vector<Parameter> parameters() { return {with_default(number("surfacePosition", "length"), 0.0)}; }
    static std::vector<Parameter> type_parameters() { return {number("epsilon", "energy/length^2")}; }
    static std::vector<std::string> ignored_type_columns() { return {"sigma"}; }

    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return {R(v["surfacePosition"]), R(v["epsilon"])};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> r, R, const Params<R>& p, R, Vec3<R>& force) {
        const R depth = p.position - r.z;
        force = {R(0), R(0), R(0)};
        if (!(depth >= R(0))) return R(0);
        force.z = p.epsilon * depth;
        return R(0.5) * p.epsilon * depth * depth;
    }
};

}  // namespace structmd
