#pragma once
// The energy terms structmd_get_energy takes: "potential", "kinetic", "total" or a forceField entry
// name, each optionally followed by "@batch:K" for the share of the particles of batch K.
#include <string>
#include <vector>

namespace structmd {

struct EnergyRequest {
    std::string term;
    int batch = -1;  // -1: every particle
};

// batchIds: the batchId of each particle. With one batch, "@batch:K" for that batch is everything.
// Throws ERR_ARGUMENT for a batch no particle has, or a term not in `entries`.
EnergyRequest parse_energy_request(const std::string& request, const std::vector<int>& batchIds,
                                   const std::vector<std::string>& entries);

}  // namespace structmd
