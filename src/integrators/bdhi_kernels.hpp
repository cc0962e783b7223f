#pragma once
// The kernels every Brownian-dynamics-with-hydrodynamics integrator shares (open boundary, force
// coupling, positively split Ewald, quasi-2D): the forces and the noise as flat vectors of 3N numbers
// (particle i's components at 3i, 3i+1, 3i+2, as the mobility products read them), and the move
//   x += dt (M F) + sqrt(2 kT dt) (M^{1/2} W) + (a displacement a mesh made whole),
// with its bookkeeping. Particles outside the integrator's group take no part and do not move.
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "core/vec.hpp"
#include "integrators/integrator.hpp"
#include "integrators/thermal_noise.hpp"
#include "state/fault.hpp"

namespace structmd {

// The tolerance of a method on a grid (force coupling, positively split Ewald, quasi-2D): the range
// its grid and Gaussian are chosen for.
inline void validate_grid_tolerance(const ParameterValues& v, const std::string& path) {
    if (!(v["tolerance"] >= 1e-10 && v["tolerance"] <= 0.1))
        throw input_error(path + ".parameters.tolerance",
                          "expected a tolerance in [1e-10, 0.1], got " + std::to_string(v["tolerance"]));
}

template <class R>
struct FlattenForces {
    const Real4<R>* force;
    R* flat;
    SMD_HD void operator()(int64_t i) const {
        const Real4<R> f = force[i];
        flat[3 * i] = f.x;
        flat[3 * i + 1] = f.y;
        flat[3 * i + 2] = f.z;
    }
};

// W ~ N(0, I) for the group's particles, keyed by their global id, 0 for the others (so that no
// noise reaches them). `purpose` keeps apart the draws of one step that must be independent (the
// noise and the random finite difference's W').
template <class R>
struct DrawHydrodynamicNoise {
    const uint8_t* group;
    NoiseKey noise;
    ClockView now;
    R* w;
    NoisePurpose purpose = NoisePurpose::integrator;
    SMD_HD void operator()(int64_t i) const {
        Vec3<R> xi{R(0), R(0), R(0)};
        if (!group || group[i]) xi = gaussian3<R>(noise, purpose, i, now.step());
        w[3 * i] = xi.x;
        w[3 * i + 1] = xi.y;
        w[3 * i + 2] = xi.z;
    }
};

// move = dt drift + spread noise + displacement, each part left out where its array is null
// (spread = sqrt(2 kT dt); noise is null at kT = 0). Every particle's drift is bookkept.
template <class R>
struct BdhiMove {
    Real4<R>* pos;
    Image* image;
    const Real4<R>* force;
    const R* drift;         // M F
    const R* noise;         // M^{1/2} W
    const R* displacement;  // dt M F + spread M^{1/2} W already, from a mesh
    const uint8_t* group;
    Box<R> box;
    R dt, spread;
    FaultSlot fault;
    DriftBookkeeping<R> bookkeeping;
    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) {
            bookkeeping(i, pos[i]);
            return;
        }
        Vec3<R> move{R(0), R(0), R(0)};
        if (drift) move += dt * Vec3<R>{drift[3 * i], drift[3 * i + 1], drift[3 * i + 2]};
        if (noise) move += spread * Vec3<R>{noise[3 * i], noise[3 * i + 1], noise[3 * i + 2]};
        if (displacement) move += Vec3<R>{displacement[3 * i], displacement[3 * i + 1], displacement[3 * i + 2]};
        fault.check_move(i, move);
        const Real4<R> p = displaced(pos[i], move, box, image[i]);
        pos[i] = p;
        fault.check(i, p, force[i]);
        bookkeeping(i, p);
    }
};

}  // namespace structmd
