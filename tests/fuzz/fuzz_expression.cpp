// libFuzzer target: the input bytes are the energy text of an ["External","Expression"] entry (of x,
// y, z, t), then of a ["Bond2","Expression"] entry (of r), each in a fixed small document that is
// loaded and stepped: the expression parser, its derivatives and the bytecode see the bytes
// unwrapped by any JSON.
#include <cstdint>
#include <cstdio>
#include <string>

#include "fuzz_contract.hpp"

using structmd::fuzz::checked;

namespace {

// The bytes as a JSON string literal, every one kept (control bytes escaped).
std::string json_string(const uint8_t* data, size_t size) {
    std::string text = "\"";
    for (size_t k = 0; k < size; ++k) {
        const unsigned char c = data[k];
        if (c == '"' || c == '\\') {
            text += '\\';
            text += static_cast<char>(c);
        } else if (c < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
            text += escaped;
        } else {
            text += static_cast<char>(c);
        }
    }
    return text + "\"";
}

std::string document(const std::string& term) {
    return R"({
  "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "fuzz", "seed": 3}}},
  "global": {"types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                       "data": [["A", 1.0, 0.5, 0.0]]},
             "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[8.0, 8.0, 8.0], 1.0]]}},
  "state": {"labels": ["id", "position"], "data": [[0, [0, 0, 0]], [1, [1.1, 0, 0]], [2, [1.6, 1.0, 0]]]},
  "topology": {"structure": {"labels": ["id", "type"], "data": [[0, "A"], [1, "A"], [2, "A"]]},
    "forceField": {"term": )" + term + R"(}},
  "integrator": {"vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.002}},
                 "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"], "data": [[1, "vv", 10]]}}
})";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string energy = json_string(data, size);
    structmd_sim* sim = nullptr;
    checked("structmd_create", structmd_create(structmd::fuzz::kHandleOptions, &sim), nullptr);
    for (const std::string& term :
         {R"({"type": ["External", "Expression"], "parameters": {"energy": )" + energy + "}}",
          R"({"type": ["Bond2", "Expression"], "parameters": {"energy": )" + energy +
              R"(}, "labels": ["id_i", "id_j"], "data": [[0, 1]]})"}) {
        const std::string text = document(term);
        if (checked("structmd_load_string", structmd_load_string(sim, text.c_str()), sim) != STRUCTMD_OK) continue;
        checked("structmd_step", structmd_step(sim, 3), sim);
        double total = 0.0;
        checked("structmd_get_energy", structmd_get_energy(sim, "total", &total), sim);
    }
    structmd_destroy(sim);
    return 0;
}
