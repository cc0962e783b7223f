#pragma once
// UAMMD-structured's rotational alignment potential (RAP) between the orientations of two bonded
// particles, A = R(q_i) and B = R(q_j) (columns: the body axes in the lab frame), and a target
// relative rotation R0 (the bond's quaternion "R"):
//   U = K/4 (3 - tr(A R0 B^T)) = K/4 (3 - sum_k a'_k . b_k),   a'_k = (A R0)_k, b_k = B_k,
// zero when B = A R0 (j's frame is i's turned by R0, in i's frame) and 2K at the farthest. Its torques
// (lab frame) are tau_i = K/4 sum_k a'_k x b_k and tau_j = -tau_i (U does not change when both turn
// together); it exerts no force. ["Bond2","HarmonicRAP"] adds a harmonic spring between a point fixed
// in each body, x_i + A c_left and x_j + B c_right:
//   U_h = Khrm/2 (|d| - r0)^2,  d = x_j + B c_right - x_i - A c_left,
// whose force acts at those points: F_i = -F_j = U_h'(|d|) d/|d|, tau_i += (A c_left) x F_i,
// tau_j += (B c_right) x F_j.
#include <cmath>
#include <memory>
#include <vector>

#include "core/quaternion.hpp"
#include "forcefield/bonded_geometry.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "forcefield/oriented_bond_interaction.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

namespace rap_detail {

// The columns of R(q) for a quaternion q = [q0, q1, q2, q3], normalised here (the reader has checked
// that it is of unit norm to the digits an input prints).
template <class R>
struct Frame {
    Vec3<R> axis[3];
};

template <class R>
SMD_HD SMD_INLINE Frame<R> frame_of(const Real4<R>& q) {
    return {{body_x(q), body_y(q), body_z(q)}};
}

template <class R>
Frame<R> target_frame(const std::vector<double>& q) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const Frame<double> f = frame_of(Real4<double>{q[0] / n, q[1] / n, q[2] / n, q[3] / n});
    Frame<R> out;
    for (int k = 0; k < 3; ++k) out.axis[k] = {R(f.axis[k].x), R(f.axis[k].y), R(f.axis[k].z)};
    return out;
}

// M v: the vector of body coordinates v in the frame M.
template <class R>
SMD_HD SMD_INLINE Vec3<R> in_frame(const Frame<R>& m, const Vec3<R>& v) {
    return v.x * m.axis[0] + v.y * m.axis[1] + v.z * m.axis[2];
}

// The alignment energy of frames a and b with target `target`, and the torque on a's particle.
template <class R>
SMD_HD SMD_INLINE R alignment(const Frame<R>& a, const Frame<R>& b, const Frame<R>& target, R K, Vec3<R>& torqueOnA) {
    R overlap = R(0);
    torqueOnA = {R(0), R(0), R(0)};
    for (int k = 0; k < 3; ++k) {
        const Vec3<R> wanted = in_frame(a, target.axis[k]);  // (A R0)_k: where b_k should point
        overlap += dot(wanted, b.axis[k]);
        torqueOnA += bonded_geometry::cross(wanted, b.axis[k]);
    }
    torqueOnA = (R(0.25) * K) * torqueOnA;
    return R(0.25) * K * (R(3) - overlap);
}

}  // namespace rap_detail

// ["Bond2","RAP"]
struct RAPPotential {
    static constexpr int arity = 2;
    template <class R>
    struct Params {
        R K;
        rap_detail::Frame<R> target;
    };

    static std::vector<Parameter> parameters() { return {number("K", "energy"), numbers("R", 4, "1")}; }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return {R(v["K"]), rap_detail::target_frame<R>(v.vector("R"))};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>*, const Real4<R>* q, const Params<R>& p, Vec3<R>* force,
                                       Vec3<R>* torque) {
        const R e = rap_detail::alignment(rap_detail::frame_of(q[0]), rap_detail::frame_of(q[1]), p.target, p.K,
                                          torque[0]);
        torque[1] = -torque[0];
        force[0] = force[1] = {R(0), R(0), R(0)};
        return e;
    }
};

// ["Bond2","HarmonicRAP"]
struct HarmonicRAPPotential {
    static constexpr int arity = 2;
    template <class R>
    struct Params {
        HarmonicBond::Params<R> spring;
        Vec3<R> leftConnection, rightConnection;
        RAPPotential::Params<R> alignment;
    };

    static std::vector<Parameter> parameters() {
        return {number("Khrm", "energy/length^2"), number("r0", "length"), numbers("leftConnection", 3, "length"),
                numbers("rightConnection", 3, "length"), number("Krap", "energy"), numbers("R", 4, "1")};
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        const auto left = v.vec3("leftConnection"), right = v.vec3("rightConnection");
        return {{R(v["Khrm"]), R(v["r0"])},
                {R(left[0]), R(left[1]), R(left[2])},
                {R(right[0]), R(right[1]), R(right[2])},
                {R(v["Krap"]), rap_detail::target_frame<R>(v.vector("R"))}};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Real4<R>* q, const Params<R>& p, Vec3<R>* force,
                                       Vec3<R>* torque) {
        const rap_detail::Frame<R> a = rap_detail::frame_of(q[0]), b = rap_detail::frame_of(q[1]);
        const Vec3<R> left = rap_detail::in_frame(a, p.leftConnection);
        const Vec3<R> right = rap_detail::in_frame(b, p.rightConnection);
        const Vec3<R> d = (r[1] + right) - (r[0] + left);
        const PairTerm<R> spring = HarmonicBond::evaluate(dot(d, d), p.spring);
        force[0] = spring.dudr_over_r * d;
        force[1] = -force[0];
        Vec3<R> aligning;
        const R e = rap_detail::alignment(a, b, p.alignment.target, p.alignment.K, aligning);
        torque[0] = bonded_geometry::cross(left, force[0]) + aligning;
        torque[1] = bonded_geometry::cross(right, force[1]) - aligning;
        return spring.energy + e;
    }
};

// The components: bonds read by the generic bond reader once the entry is checked (a state with
// orientations, target quaternions of unit norm; rotational_alignment_read.cpp).
template <class Potential>
struct OrientedBondComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        return make_oriented_bond_interaction<Potential>(build, s);
    }
};

}  // namespace structmd
