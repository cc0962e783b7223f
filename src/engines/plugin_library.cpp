#include "engines/plugin_library.hpp"

#include <dlfcn.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "core/error.hpp"
#include "engines/plugin_abi.hpp"

namespace structmd {

namespace {

std::string dl_error() {
    const char* text = dlerror();
    return text ? text : "unknown reason";
}

}  // namespace

std::shared_ptr<const ComponentSet> load_plugin_library(const std::string& path) {
    const std::string where = "plugin '" + path + "'";
    struct stat info {};
    if (stat(path.c_str(), &info) != 0) throw Error(STRUCTMD_ERR_IO, where + ": cannot open: " + std::strerror(errno));
    // RTLD_LOCAL: two plugins' entry points do not clash. Until the checks pass, the library may be
    // unloaded again (dlclose below), so a refused plugin leaves nothing mapped.
    dlerror();
    void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library) throw Error(STRUCTMD_ERR_IO, where + ": not a loadable shared library: " + dl_error());
    struct Close {
        void* library;
        ~Close() { dlclose(library); }
    } close{library};

    const auto abi = reinterpret_cast<PluginAbiVersionFn>(dlsym(library, "structmd_plugin_abi_version"));
    const auto build = reinterpret_cast<PluginBuildFn>(dlsym(library, "structmd_plugin_build"));
    const auto add = reinterpret_cast<PluginRegisterFn>(dlsym(library, "structmd_plugin_register"));
    if (!abi || !build || !add)
        throw Error(STRUCTMD_ERR_ARGUMENT, where +
                                               ": not a structmd plugin (it does not export "
                                               "structmd_plugin_abi_version, structmd_plugin_build and "
                                               "structmd_plugin_register; define them with STRUCTMD_PLUGIN)");
    const int version = abi();
    if (version != STRUCTMD_PLUGIN_ABI_VERSION)
        throw Error(STRUCTMD_ERR_UNSUPPORTED, where + ": built for structmd plugin ABI " + std::to_string(version) +
                                                  ", but this library speaks plugin ABI " +
                                                  std::to_string(STRUCTMD_PLUGIN_ABI_VERSION) +
                                                  "; rebuild the plugin against this structmd. It was not loaded");
    const char* plugin_build = build();
    const std::string theirs = plugin_build ? plugin_build : "";
    if (theirs != STRUCTMD_PLUGIN_BUILD)
        throw Error(STRUCTMD_ERR_UNSUPPORTED, where + ": built for \"" + theirs + "\", but this library is \"" +
                                                  STRUCTMD_PLUGIN_BUILD +
                                                  "\"; rebuild the plugin against this structmd. It was not loaded");

    // Accepted: its code will run inside engines for as long as the process lives, so it is never
    // unloaded (RTLD_NODELETE on the library already loaded).
    if (!dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD | RTLD_NODELETE))
        throw Error(STRUCTMD_ERR_IO, where + ": cannot keep the library loaded: " + dl_error());

    auto set = std::make_shared<ComponentSet>();
    set->source = path;
    char message[1024] = "";
    const int status = add(set.get(), message, sizeof message);
    message[sizeof message - 1] = '\0';  // a plugin that filled the buffer to its end wrote no NUL
    if (status != STRUCTMD_OK) {
        // The plugin's status is the call's only when the header defines it: a host checks for those.
        const bool headerStatus = status > STRUCTMD_OK && status <= STRUCTMD_ERR_CALLBACK;
        throw Error(headerStatus ? static_cast<structmd_status>(status) : STRUCTMD_ERR_ARGUMENT,
                    where + ": registration failed" +
                        (headerStatus ? "" : " with status " + std::to_string(status) + ", which is not a structmd status") +
                        ": " + message);
    }
    if (set->reader.entries().empty() && set->transversers.empty()) throw Error(STRUCTMD_ERR_ARGUMENT, where + ": registers no component");
    return set;
}

}  // namespace structmd
