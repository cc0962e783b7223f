#include "simulation/energy_terms.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace structmd {

EnergyRequest parse_energy_request(const std::string& request, const std::vector<int>& batchIds,
                                   const std::vector<std::string>& entries) {
    EnergyRequest parsed{request, -1};
    const size_t at = request.find("@batch:");
    if (at != std::string::npos) {
        parsed.term = request.substr(0, at);
        const std::string text = request.substr(at + 7);
        size_t used = 0;
        int batch = -1;
        try {
            batch = std::stoi(text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != text.size() || std::find(batchIds.begin(), batchIds.end(), batch) == batchIds.end())
            throw Error(STRUCTMD_ERR_ARGUMENT, "energy term '" + request + "': no particle has batchId '" + text + "'");
        const bool oneBatch = std::all_of(batchIds.begin(), batchIds.end(), [&](int b) { return b == batchIds[0]; });
        parsed.batch = oneBatch ? -1 : batch;
    }
    const std::string& t = parsed.term;
    const bool entry = std::find(entries.begin(), entries.end(), t) != entries.end();
    if (t == "external" && !entry) {
        if (parsed.batch >= 0)
            throw Error(STRUCTMD_ERR_ARGUMENT, "energy term '" + request +
                                                   "': the host's external energy belongs to no batch (ask for 'external')");
        parsed.host = true;
        return parsed;
    }
    if (t == "callback" && !entry) {
        if (parsed.batch >= 0)
            throw Error(STRUCTMD_ERR_ARGUMENT, "energy term '" + request +
                                                   "': the force callbacks' energy belongs to no batch (ask for 'callback')");
        parsed.callback = true;
        return parsed;
    }
    if (t == "potential" || t == "kinetic" || t == "total" || entry) return parsed;
    std::string known = "potential, kinetic, total, external, callback";
    for (const std::string& name : entries) known += ", " + name;
    throw Error(STRUCTMD_ERR_ARGUMENT,
                "energy term '" + request + "' does not exist (terms: " + known + ", each optionally followed by @batch:K)");
}

}  // namespace structmd
