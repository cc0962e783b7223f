#pragma once
// The message for a numerical fault recorded on the backend (state/fault.hpp's word).
#include <cstdint>
#include <string>

namespace structmd {

// skin: the thinnest list skin (the longest move allowed in one step); failedStep: where the run
// got to; backAt: the step the state was returned to.
std::string describe_fault(unsigned long long word, double skin, int64_t failedStep, int64_t backAt);

}  // namespace structmd
