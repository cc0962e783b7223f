#pragma once
// The potentials of the Set1 and Set2 components: terms on the centres of mass of sets of particles
// (set_interaction.hpp computes the centres and spreads the result over the members).
//
// A term on centres of mass is a bond whose "particles" are those centres: the same contract as
// bond_potential.hpp (arity = sets per row), so the Set components reuse the bond functors
// (["Bond1","ConstantForce"], ["Bond1","FixedHarmonicAnisotropic"], ["Bond2","Harmonic"]) and add
// only what has no bond of its own. A torque term instead declares `torque = true` and gives, from
// the centres, the torque on each set (SetTorque contract below).
#include <array>
#include <type_traits>
#include <vector>

#include "forcefield/constant_force_bond.hpp"
#include "forcefield/harmonic_anisotropic.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {

// Whether a set potential is a torque (has `static constexpr bool torque = true`).
template <class P, class = void>
struct is_set_torque : std::false_type {};
template <class P>
struct is_set_torque<P, std::void_t<decltype(P::torque)>> : std::bool_constant<P::torque> {};

// ["Set2","ConstantForceBetweenCentersOfMass"] as a radial term: a force of constant size F along the
// line of the two centres, pushing them apart for F > 0 (UAMMD-structured's force), with the energy
// U = -F r whose gradient it is (UAMMD-structured writes +F r, the gradient of the opposite force).
struct ConstantForceRadial {
    template <class R>
    struct Params {
        R F;
    };
    static std::vector<Parameter> bond_parameters() { return {number("force", "force")}; }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants&) {
        return {R(v["force"])};
    }
    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        const R r = sqrt(r2);
        PairTerm<R> term;
        // Coincident centres give no direction: no force there rather than NaN.
        term.dudr_over_r = r > R(0) ? -p.F / r : R(0);
        term.energy = -p.F * r;
        return term;
    }
};

// ["Set1","FixedHarmonicAnisotropicCommon_K_r0CenterOfMass"]: FixedHarmonicAnisotropic with one K and
// one r0 (numbers, given once in the entry's "parameters") for all three axes.
struct FixedHarmonicIsotropicCommon {
    static constexpr int arity = 1;
    template <class R>
    using Params = FixedHarmonicAnisotropic::Params<R>;

    static std::vector<Parameter> entry_parameters() {
        return {number("K", "energy/length^2"), number("r0", "length", Must::be_non_negative)};
    }
    static std::vector<Parameter> parameters() { return {numbers("position", 3, "length")}; }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        const R K = R(v["K"]), r0 = R(v["r0"]);
        const std::array<double, 3> point = v.vec3("position");
        return {{{K, K, K}, {r0, r0, r0}}, {R(point[0]), R(point[1]), R(point[2])}};
    }
    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>& box, Vec3<R>* force) {
        return FixedHarmonicAnisotropic::compute(r, p, box, force);
    }
};

// The SetTorque contract: arity sets; torques(c, p, box, T) writes the torque T[s] about set s's
// centre, given the centres c (c[1] the minimum image of the second centre seen from c[0]). The
// interactor turns a torque into member forces with no net force (set_interaction.hpp).

// ["Set1","ConstantTorqueOverCenterOfMass"]: a constant torque vector on one set.
struct ConstantTorqueOnSet {
    static constexpr int arity = 1;
    static constexpr bool torque = true;
    template <class R>
    struct Params {
        Vec3<R> torque;
    };
    static std::vector<Parameter> parameters() { return {numbers("torque", 3, "energy")}; }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        const std::array<double, 3> t = v.vec3("torque");
        return {{R(t[0]), R(t[1]), R(t[2])}};
    }
    template <class R>
    static SMD_HD SMD_INLINE void torques(const Vec3<R>*, const Params<R>& p, const Box<R>&, Vec3<R>* T) {
        T[0] = p.torque;
    }
};

// ["Set2","ConstantTorqueBetweenCentersOfMass"]: torques of size `torque` along the axis joining the
// two centres, T on the first set along c1 - c0 and -T on the second (they twist in opposite senses
// about their common axis).
struct ConstantTorqueBetweenSets {
    static constexpr int arity = 2;
    static constexpr bool torque = true;
    template <class R>
    struct Params {
        R torque;
    };
    static std::vector<Parameter> parameters() { return {number("torque", "energy")}; }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return {R(v["torque"])};
    }
    template <class R>
    static SMD_HD SMD_INLINE void torques(const Vec3<R>* c, const Params<R>& p, const Box<R>&, Vec3<R>* T) {
        const Vec3<R> axis = c[1] - c[0];
        const R length2 = dot(axis, axis);
        // Coincident centres define no axis: no torque.
        T[0] = length2 > R(0) ? R(p.torque / sqrt(length2)) * axis : Vec3<R>{R(0), R(0), R(0)};
        T[1] = -T[0];
    }
};

}  // namespace structmd
