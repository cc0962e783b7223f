// libFuzzer target: the input bytes are a document for structmd_load_string on a fresh handle. A
// document that loads is stepped a few times, since some inputs only fail once the engine runs them.
#include <cstdint>
#include <string>

#include "fuzz_contract.hpp"

using structmd::fuzz::checked;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);  // adds the NUL the API needs
    structmd_sim* sim = nullptr;
    checked("structmd_create", structmd_create(structmd::fuzz::kHandleOptions, &sim), nullptr);
    if (checked("structmd_load_string", structmd_load_string(sim, text.c_str()), sim) == STRUCTMD_OK) {
        checked("structmd_step", structmd_step(sim, 3), sim);
        double energy = 0.0;
        checked("structmd_get_energy", structmd_get_energy(sim, "total", &energy), sim);
    }
    structmd_destroy(sim);
    return 0;
}
