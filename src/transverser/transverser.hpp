#pragma once
// The Transverser contract: a computation over pairs of particles that the user writes once and the
// engine runs on every backend, over a neighbour list (neighbour_traversal.hpp) or over all pairs
// (all_pairs_traversal.hpp). It is UAMMD's Transverser concept; a pair potential is the special case
// whose Compute is a force, an energy and a virial.
//
// A transverser T is a struct, copied by value into the kernel (plain data and pointers to backend
// memory), with two types of its choosing and five functions, all SMD_HD:
//
//   using Info = ...;     // what one particle brings to a pair: its charge, its mass, its index...
//   using Compute = ...;  // what one pair gives and a particle's total holds: a count, a force...
//   Compute zero() const;                               // a total before any pair
//   Info info(int i) const;                             // particle i's Info (i: its index)
//   Compute compute(const Real4<R>& ri, const Real4<R>& rj,
//                   const Info& infoI, const Info& infoJ) const;  // what pair (i, j) gives i
//   void accumulate(Compute& total, const Compute& current) const;  // total += current
//   void set(int i, const Compute& total) const;        // writes particle i's total (anywhere)
//
// ri and rj are the pair's positions in the frame of particle i (w: each one's type): ri at the
// origin and rj at the separation r_j - r_i, of the periodic image of j nearest i. So xyz(rj) -
// xyz(ri) is the separation, taken once in R (as the pair terms take it: its accuracy does not fall
// with the size of the box), and no box is needed; a transverser that needs absolute positions
// reads them in info(). compute() is called for every ordered pair (i, j), i != j, that the
// traversal offers, so each particle gets its own total (no atomics).
// The traversal splits a particle's pairs among lanes (core/lanes.hpp) on the GPU and combines the
// lanes' totals with accumulate: accumulate must be associative and commutative (a sum, a max), and
// Compute trivially copyable. Info must be plain data too: over all pairs of a large system the GPU
// copies the partners' Info into shared-memory tiles (all_pairs_traversal.hpp). set() is called once
// per particle traversed, with its full total; without a group that is every particle, so it must
// write all of what the caller reads (the engine zeroes an output only for a group).
// What the host prepares (uploading a table) it does before building the struct.
#include "core/hd.hpp"
#include "core/vec.hpp"

namespace structmd {

// The pair (i, j) in the frame of i: positions pi and pj (w: the types) become first = (0, 0, 0,
// type_i) and second = (minimum image of r_j - r_i, type_j).
template <class R>
struct PairFrame {
    Real4<R> first, second;
};

template <class R, class Box>
SMD_HD SMD_INLINE PairFrame<R> pair_frame(const Real4<R>& pi, const Real4<R>& pj, const Box& box) {
    const Vec3<R> d = box.minimum_image(xyz(pj) - xyz(pi));
    return {Real4<R>{R(0), R(0), R(0), pi.w}, Real4<R>{d.x, d.y, d.z, pj.w}};
}

}  // namespace structmd
