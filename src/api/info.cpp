// structmd_get_info: the handle described as JSON.
#include <nlohmann/json.hpp>

#include "api/handle.hpp"
#include "parallel/communicator.hpp"
#include "parallel/replica_exchange.hpp"

using namespace structmd;
using namespace structmd::api;

extern "C" {

structmd_status structmd_get_info(const structmd_sim* sim, char* buffer, size_t size, size_t* needed) {
    return with_handle(sim, [&](const structmd_sim& s) {
        nlohmann::json info;
        info["version"] = STRUCTMD_VERSION_STRING;
        info["backend"] = name_of(s.options.backend);
        info["precision"] = name_of(s.options.precision);
        info["precisions_compiled"] = compiled_precisions();
        info["loaded"] = static_cast<bool>(s.simulation);
        info["device"] = device_description(s.options);
        info["threads"] = s.options.backend == BackendKind::cpu ? cpu_thread_count(s.options) : 0;
        info["mpi"] = {{"compiled", mpi_compiled()},
                       {"ranks", s.communicator ? s.communicator->size() : 1},
                       {"rank", s.communicator ? s.communicator->rank() : 0},
                       {"node_rank", s.communicator ? s.communicator->node_rank() : 0},
                       {"nccl", nccl_compiled()}};
        if (s.simulation) {
            info["particles"] = s.simulation->particle_count();
            info["final_step"] = s.simulation->final_step();
            const std::string& stoppedBy = s.simulation->stopped_by();
            info["stopped_by"] = stoppedBy.empty() ? nlohmann::json(nullptr) : nlohmann::json(stoppedBy);
            if (const auto* exchange = dynamic_cast<const ReplicaExchange*>(s.simulation.get())) {
                std::vector<double> acceptance;
                for (size_t k = 0; k < exchange->attempts().size(); ++k)
                    acceptance.push_back(exchange->attempts()[k] > 0 ? static_cast<double>(exchange->accepted()[k]) /
                                                                           static_cast<double>(exchange->attempts()[k])
                                                                     : 0.0);
                info["replica_exchange"] = {{"temperatures", exchange->spec().temperatures},
                                            {"attempts", exchange->attempts()},
                                            {"accepted", exchange->accepted()},
                                            {"acceptance", acceptance}};
            }
        } else {
            info["particles"] = 0;
            info["final_step"] = -1;
            info["stopped_by"] = nullptr;
        }
        const std::string text = info.dump();
        if (needed) *needed = text.size() + 1;
        copy_text(text, buffer, size);
    });
}

}  // extern "C"
