#pragma once
// Reading the table of an entry whose rows name sets of particles (Set1, Set2, AFM): per row, one list
// of particle ids per set label and the row's parameters (a parameter with a default is an optional
// column). A set that is empty, names an unknown particle, or shares a particle with another set of
// the entry is an input error naming the cell.
#include <memory>
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "forcefield/set_interaction.hpp"
#include "input/description.hpp"

namespace structmd {

std::shared_ptr<SetConfig> read_set_table(const input::ComponentEntry& entry, const input::SystemDescription& system,
                                          const std::vector<std::string>& setLabels,
                                          const std::vector<Parameter>& schema);

}  // namespace structmd
