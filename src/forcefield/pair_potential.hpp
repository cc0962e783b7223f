#pragma once
// The contract of a radial pair potential (non-bonded or a two-body bond): a host+device functor
// with a Params struct and evaluate(r2, params) returning U'(r)/r and U(r). The force on i from j is
// F_i = (U'(r)/r) r_ij with r_ij = r_j - r_i, and F_j = -F_i.
#include <cmath>

#include "core/hd.hpp"

namespace structmd {

template <class R>
struct PairTerm {
    R dudr_over_r;
    R energy;
};

}  // namespace structmd
