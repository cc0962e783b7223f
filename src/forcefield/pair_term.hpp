#pragma once
// What a radial pair potential returns for one distance (pair_potential.hpp): U'(r)/r and U(r).
#include "core/hd.hpp"

namespace structmd {

template <class R>
struct PairTerm {
    R dudr_over_r;
    R energy;
};

}  // namespace structmd
