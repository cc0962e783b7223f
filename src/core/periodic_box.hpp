#pragma once
// The check of the components whose grids, cells or sums span the periodic box (Ewald electrostatics,
// the hydrodynamics on grids, the stress measure's cells): a box with an open axis (core/box.hpp) is
// refused at the component's path.
#include <array>
#include <string>

#include "core/box.hpp"
#include "core/error.hpp"

namespace structmd {

inline void require_periodic_box(const std::array<double, 3>& box, const std::string& path, const std::string& what) {
    if (has_open_axis(box[0], box[1], box[2]))
        throw input_error(path, what + " needs a box periodic along every axis; this box has an open axis (a length "
                                       "of 0 or \"inf\")");
}

}  // namespace structmd
