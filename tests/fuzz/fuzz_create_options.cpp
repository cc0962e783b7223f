// libFuzzer target: the input bytes are the options string of structmd_create. A handle that is
// created describes itself and loads a small document; it is not stepped, since options may ask for
// any number of threads.
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_contract.hpp"

using structmd::fuzz::checked;

namespace {

const char* const kDocument = R"({
  "global": {"types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                       "data": [["A", 1.0, 0.5, 0.0]]},
             "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[8.0, 8.0, 8.0], 1.0]]}},
  "state": {"labels": ["id", "position"], "data": [[0, [0, 0, 0]], [1, [1.1, 0, 0]]]},
  "topology": {"structure": {"labels": ["id", "type"], "data": [[0, "A"], [1, "A"]]},
    "forceField": {"bonds": {"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"], "data": [[0, 1, 100, 1]]}}}
})";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string options(reinterpret_cast<const char*>(data), size);  // adds the NUL the API needs
    structmd_sim* sim = nullptr;
    if (checked("structmd_create", structmd_create(options.c_str(), &sim), nullptr) != STRUCTMD_OK) return 0;
    size_t needed = 0;
    checked("structmd_get_info", structmd_get_info(sim, nullptr, 0, &needed), sim);
    std::vector<char> info(needed);
    checked("structmd_get_info", structmd_get_info(sim, info.data(), info.size(), &needed), sim);
    checked("structmd_load_string", structmd_load_string(sim, kDocument), sim);
    structmd_destroy(sim);
    return 0;
}
