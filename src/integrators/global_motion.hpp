#pragma once
// Removal of a group's global translation and rotation from its velocities (BBK's
// stopTransRotSteps): v_i -= V + omega x (r_i - R), with V the centre-of-mass velocity, R the centre
// of mass and omega = I^-1 L the angular velocity that carries the angular momentum L about R
// (I the inertia tensor about R). Positions are unwrapped (a cluster split by the box is one body)
// and taken half a step back, where the leapfrog's half-step velocities belong.
//
// One pass sums the moments about the origin in double; the host moves them to R (parallel-axis
// theorem), solves for omega, and one kernel corrects the velocities.
#include <cmath>

#include "integrators/integrator.hpp"

namespace structmd {

// Sums over the particles of m, m r, m v, m r x v and the second moments m r_a r_b.
struct MassMoments {
    double mass = 0;
    double mr[3] = {0, 0, 0};
    double mv[3] = {0, 0, 0};
    double rxv[3] = {0, 0, 0};
    double rr[6] = {0, 0, 0, 0, 0, 0};  // xx, yy, zz, xy, xz, yz
};

SMD_HD SMD_INLINE MassMoments operator+(const MassMoments& a, const MassMoments& b) {
    MassMoments s;
    s.mass = a.mass + b.mass;
    for (int k = 0; k < 3; ++k) {
        s.mr[k] = a.mr[k] + b.mr[k];
        s.mv[k] = a.mv[k] + b.mv[k];
        s.rxv[k] = a.rxv[k] + b.rxv[k];
    }
    for (int k = 0; k < 6; ++k) s.rr[k] = a.rr[k] + b.rr[k];
    return s;
}

// Unwrapped position half a step before the current one: x(n+1) - dt/2 v(n+1/2).
template <class R>
SMD_HD SMD_INLINE void midpoint(const Real4<R>& p, const Image& image, const Real4<R>& v, const Box<R>& box, R dt,
                                double r[3]) {
    r[0] = double(p.x) + Box<double>::image_offset(image.x, double(box.length.x)) - 0.5 * double(dt) * double(v.x);
    r[1] = double(p.y) + Box<double>::image_offset(image.y, double(box.length.y)) - 0.5 * double(dt) * double(v.y);
    r[2] = double(p.z) + Box<double>::image_offset(image.z, double(box.length.z)) - 0.5 * double(dt) * double(v.z);
}

template <class R>
struct SumMassMoments {
    const Real4<R>* pos;
    const Image* image;
    const Real4<R>* vel;  // the mass rides in w
    const uint8_t* group;
    Box<R> box;
    R dt;
    SMD_HD MassMoments operator()(int64_t i) const {
        MassMoments s;
        if (group && !group[i]) return s;
        const Real4<R> v = vel[i];
        double r[3];
        midpoint(pos[i], image[i], v, box, dt, r);
        const double m = double(v.w);
        const double u[3] = {double(v.x), double(v.y), double(v.z)};
        s.mass = m;
        for (int k = 0; k < 3; ++k) {
            s.mr[k] = m * r[k];
            s.mv[k] = m * u[k];
        }
        s.rxv[0] = m * (r[1] * u[2] - r[2] * u[1]);
        s.rxv[1] = m * (r[2] * u[0] - r[0] * u[2]);
        s.rxv[2] = m * (r[0] * u[1] - r[1] * u[0]);
        s.rr[0] = m * r[0] * r[0];
        s.rr[1] = m * r[1] * r[1];
        s.rr[2] = m * r[2] * r[2];
        s.rr[3] = m * r[0] * r[1];
        s.rr[4] = m * r[0] * r[2];
        s.rr[5] = m * r[1] * r[2];
        return s;
    }
};

// The rigid motion to remove: v(r) = velocity + omega x (r - centre).
struct RigidMotion {
    double centre[3] = {0, 0, 0};
    double velocity[3] = {0, 0, 0};
    double omega[3] = {0, 0, 0};
};

// V = P / M; L and I moved from the origin to the centre of mass R; omega = I^-1 L. Where I is
// singular (one particle, or all on a line, whose spin about the line is undefined) no rotation is
// removed.
inline RigidMotion rigid_motion(const MassMoments& s) {
    RigidMotion motion;
    if (!(s.mass > 0)) return motion;
    const double M = s.mass;
    double* c = motion.centre;
    for (int k = 0; k < 3; ++k) {
        c[k] = s.mr[k] / M;
        motion.velocity[k] = s.mv[k] / M;
    }
    const double* V = motion.velocity;
    // L_R = sum m (r - R) x (v - V) = sum m r x v - M R x V
    const double L[3] = {s.rxv[0] - M * (c[1] * V[2] - c[2] * V[1]), s.rxv[1] - M * (c[2] * V[0] - c[0] * V[2]),
                         s.rxv[2] - M * (c[0] * V[1] - c[1] * V[0])};
    // Second moments about R: S_ab = sum m r_a r_b - M R_a R_b; I = tr(S) 1 - S.
    const double Sxx = s.rr[0] - M * c[0] * c[0], Syy = s.rr[1] - M * c[1] * c[1], Szz = s.rr[2] - M * c[2] * c[2];
    const double Sxy = s.rr[3] - M * c[0] * c[1], Sxz = s.rr[4] - M * c[0] * c[2], Syz = s.rr[5] - M * c[1] * c[2];
    const double Ixx = Syy + Szz, Iyy = Sxx + Szz, Izz = Sxx + Syy, Ixy = -Sxy, Ixz = -Sxz, Iyz = -Syz;
    // Inverse by cofactors.
    const double Cxx = Iyy * Izz - Iyz * Iyz, Cxy = Ixz * Iyz - Ixy * Izz, Cxz = Ixy * Iyz - Ixz * Iyy;
    const double Cyy = Ixx * Izz - Ixz * Ixz, Cyz = Ixy * Ixz - Ixx * Iyz, Czz = Ixx * Iyy - Ixy * Ixy;
    const double det = Ixx * Cxx + Ixy * Cxy + Ixz * Cxz;
    const double scale = Ixx + Iyy + Izz;
    if (!(std::abs(det) > 1e-12 * scale * scale * scale)) return motion;
    motion.omega[0] = (Cxx * L[0] + Cxy * L[1] + Cxz * L[2]) / det;
    motion.omega[1] = (Cxy * L[0] + Cyy * L[1] + Cyz * L[2]) / det;
    motion.omega[2] = (Cxz * L[0] + Cyz * L[1] + Czz * L[2]) / det;
    return motion;
}

template <class R>
struct RemoveRigidMotion {
    const Real4<R>* pos;
    const Image* image;
    Real4<R>* vel;
    const uint8_t* group;
    Box<R> box;
    R dt;
    RigidMotion motion;
    SMD_HD void operator()(int64_t i) const {
        if ((group && !group[i]) || held_fixed(vel[i])) return;
        Real4<R> v = vel[i];
        double r[3];
        midpoint(pos[i], image[i], v, box, dt, r);
        const double* w = motion.omega;
        const double d[3] = {r[0] - motion.centre[0], r[1] - motion.centre[1], r[2] - motion.centre[2]};
        v.x -= R(motion.velocity[0] + (w[1] * d[2] - w[2] * d[1]));
        v.y -= R(motion.velocity[1] + (w[2] * d[0] - w[0] * d[2]));
        v.z -= R(motion.velocity[2] + (w[0] * d[1] - w[1] * d[0]));
        vel[i] = v;
    }
};

// Removes the global translation and rotation of the group's particles (all when group is null).
template <class B, class R>
void remove_rigid_motion(const B& backend, Particles<B, R>& p, const uint8_t* group, R dt) {
    const MassMoments sums = backend.reduce(
        p.count, SumMassMoments<R>{p.pos.data(), p.image.data(), p.vel.data(), group, p.box, dt}, MassMoments{});
    backend.for_each(p.count, RemoveRigidMotion<R>{p.pos.data(), p.image.data(), p.vel.data(), group, p.box, dt,
                                                   rigid_motion(sums)});
}

}  // namespace structmd
