#pragma once
// The columns of an ["AFM", ...] entry's table after its two sets: the tip's parameters, then the
// chip's (afm_tip.hpp), in the layout of AfmConfig's values.
#include <vector>

#include "core/parameters.hpp"

namespace structmd {

std::vector<Parameter> afm_schema(std::vector<Parameter> tip);

}  // namespace structmd
