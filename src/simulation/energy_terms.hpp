#pragma once
// The energy terms structmd_get_energy takes: "potential", "kinetic", "total", "external" (the
// host's field, structmd_set_external_energy), "callback" (the host's force callbacks) or a
// forceField entry name, each optionally followed
// by "@batch:K" for the share of the particles of batch K. An entry named "external" keeps its name:
// the host's energy then has no term of its own (it is still part of "total"); so does one named
// "callback".
#include <string>
#include <vector>

namespace structmd {

struct EnergyRequest {
    std::string term;
    int batch = -1;  // -1: every particle
    bool host = false;  // term is the host's external energy (no entry is called "external")
    bool callback = false;  // term is the force callbacks' energy (no entry is called "callback")
};

// batchIds: the batchId of each particle. With one batch, "@batch:K" for that batch is everything.
// Throws ERR_ARGUMENT for a batch no particle has, a term not in `entries`, or the host's
// "external" asked for one batch of several (it belongs to no batch).
EnergyRequest parse_energy_request(const std::string& request, const std::vector<int>& batchIds,
                                   const std::vector<std::string>& entries);

}  // namespace structmd
