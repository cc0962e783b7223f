#pragma once
// The contract of a bonded term of N particles (N = 1..4): a host+device functor with
//   static constexpr int arity;                         // N
//   template <class R> struct Params { ... };           // plain, copyable to the device
//   static std::vector<Parameter> parameters();         // what its input gives, by name
//   template <class R> static Params<R> make_params(const ParameterValues& v, const Constants& c);
//   template <class R> static SMD_HD R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>& box,
//                                              Vec3<R>* force);
// compute() receives the N positions made consistent across periodic boundaries (r[0] is the first
// particle's wrapped position, r[k] = r[k-1] + minimum_image(x_k - x_{k-1})) and the box (a term
// tied to a fixed point needs its minimum image), writes the force on
// each of the N particles and returns the energy. A geometry where the term has no finite energy
// (an over-stretched FENE bond) returns NaN energy and NaN forces: the engine reports it as a
// numerical error naming the step and particle.
// A bond that runs under spatial domains (parallel/domains_over_ranks.hpp: a domain evaluates every
// bond of a particle it owns, its partners held as ghosts) has `static constexpr bool under_domains = true`.
#include "core/box.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {

// Adapts a radial pair potential (pair_potential.hpp) to a two-particle bond.
template <class Radial>
struct RadialBond {
    static constexpr int arity = 2;
    static constexpr bool under_domains = true;  // reader_entries.hpp: runs_under_domains
    template <class R>
    using Params = typename Radial::template Params<R>;

    static std::vector<Parameter> parameters() { return Radial::bond_parameters(); }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants& c) {
        return Radial::template make_bond_params<R>(v, c);
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        const Vec3<R> d = r[1] - r[0];
        const PairTerm<R> t = Radial::evaluate(dot(d, d), p);
        force[0] = t.dudr_over_r * d;
        force[1] = -force[0];
        return t.energy;
    }
};

}  // namespace structmd
