// A plugin that passes the version checks, then fails its registration with a status the header does
// not define and a message that fills the whole buffer with no NUL.
#include <cstring>

#include "engines/plugin_abi.hpp"

#define EXPORTED extern "C" __attribute__((visibility("default")))

EXPORTED int structmd_plugin_abi_version(void) { return STRUCTMD_PLUGIN_ABI_VERSION; }
EXPORTED const char* structmd_plugin_build(void) { return STRUCTMD_PLUGIN_BUILD; }
EXPORTED int structmd_plugin_register(structmd::ComponentSet*, char* message, size_t size) {
    std::memset(message, 'x', size);
    return 42;
}
