#pragma once
// The contract of an external potential acting on each particle alone: a host+device functor with
//   template <class R> struct Params { ... };
//   template <class R> static SMD_HD R compute(Vec3<R> r, R radius, const Params<R>& p, R time,
//                                              Vec3<R>& force);
// r is the particle's wrapped position (external fields see no periodic images), radius its radius,
// time the simulation time (for moving walls). compute() writes the force -grad U and returns U.
#include "core/hd.hpp"
#include "core/vec.hpp"
