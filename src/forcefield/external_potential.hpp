#pragma once
// The contract of an external potential acting on each particle alone: a host+device functor with
//   template <class R> struct Params { ... };
//   static std::vector<Parameter> parameters();   // its entry's "parameters", by name
//   template <class R> static Params<R> make_params(const ParameterValues& v, const Constants& c);
//   template <class R> static SMD_HD R compute(Vec3<R> r, R radius, const Params<R>& p, R time,
//                                              Vec3<R>& force);
// r is the particle's wrapped position (external fields see no periodic images), radius its radius,
// time the simulation time (for moving walls). compute() writes the force -grad U and returns U.
#include <array>
#include <vector>

#include "core/hd.hpp"
#include "core/parameters.hpp"
#include "core/vec.hpp"
#include "forcefield/pair_potential.hpp"
