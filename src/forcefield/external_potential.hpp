#pragma once
// The contract of an external potential acting on each particle alone: a host+device functor with
//   template <class R> struct Params { ... };
//   static std::vector<Parameter> parameters();   // its entry's "parameters", by name
//   template <class R> static Params<R> make_params(const ParameterValues& v, const Constants& c);
//   template <class R> static SMD_HD R compute(Vec3<R> r, R radius, const Params<R>& p, R time,
//                                              Vec3<R>& force);
// r is the particle's wrapped position (external fields see no periodic images), radius its radius,
// time the simulation time (for moving walls). compute() writes the force -grad U and returns U.
//
// A potential whose parameters depend on the particle's type (the Surface family: eps and sigma per
// type, a surface position for the entry) also declares
//   static std::vector<Parameter> type_parameters();  // columns of the entry's table, after "name"
// Its entry then carries a table with one row per type; make_params is given the entry's values
// together with those of one row, and each particle is computed with the Params of its type. A type
// the table does not list feels nothing. Optionally
//   static std::vector<std::string> ignored_type_columns();  // accepted in the table, never read
// for columns the reference's generators write although the potential has no use for them.
#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include "core/hd.hpp"
#include "core/parameters.hpp"
#include "core/vec.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {

template <class Potential, class = void>
struct has_type_parameters : std::false_type {};
template <class Potential>
struct has_type_parameters<Potential, std::void_t<decltype(Potential::type_parameters())>> : std::true_type {};

template <class Potential, class = void>
struct has_ignored_type_columns : std::false_type {};
template <class Potential>
struct has_ignored_type_columns<Potential, std::void_t<decltype(Potential::ignored_type_columns())>>
    : std::true_type {};

}  // namespace structmd
