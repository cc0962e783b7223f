#pragma once
// Bonded groups made whole at load. An input may give positions already wrapped into the box; a
// chain that crosses a face then has bonds about a box length long in its coordinates, and every
// unwrapped output (trajectories with "wrapped": false, mean-square displacement, gyration radius)
// would show it broken. Walking each connected group of the bond graph breadth-first from its lowest
// id, each particle is moved to the periodic image nearest the particle it was reached from. An input
// whose groups are already whole keeps its coordinates: each bond is then its own minimum image.
#include <array>
#include <vector>

#include "forcefield/forcefield_spec.hpp"

namespace structmd {

// positions by particle id; bonds: every bonded term (consecutive members of a bond are connected).
void make_bonded_groups_whole(std::vector<std::array<double, 3>>& positions, const std::array<double, 3>& box,
                              const std::vector<BondSpec>& bonds);

}  // namespace structmd
