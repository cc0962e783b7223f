// Plugins: structmd_load_plugin and the components a new handle starts with.
//
// The one piece of process-wide state of the library, asked for by the C API: the list of plugin
// libraries loaded by structmd_load_plugin, guarded by a mutex. It only grows, and it is read once per
// handle, at structmd_create: a handle knows the plugins loaded before it was created (as OpenMM's
// Platform::loadPluginLibrary), plus those of its own "plugins" option, and keeps them as a value, so
// a later structmd_load_plugin never changes a handle that exists.
#include <algorithm>
#include <mutex>
#include <vector>

#include "api/handle.hpp"
#include "engines/plugin_library.hpp"

namespace structmd::api {

namespace {

struct LoadedPlugins {
    std::mutex mutex;
    std::vector<std::shared_ptr<const ComponentSet>> sets;
};

LoadedPlugins& process_plugins() {
    static LoadedPlugins plugins;
    return plugins;
}

}  // namespace

std::shared_ptr<const ForceFieldComponents> handle_components(const std::vector<std::string>& paths) {
    std::vector<std::shared_ptr<const ComponentSet>> sets;
    {
        LoadedPlugins& loaded = process_plugins();
        std::lock_guard<std::mutex> lock(loaded.mutex);
        sets = loaded.sets;
    }
    if (sets.empty() && paths.empty()) {
        static const auto builtin = std::make_shared<const ForceFieldComponents>();
        return builtin;
    }
    auto components = std::make_shared<ForceFieldComponents>();
    for (auto& set : sets) components->add(std::move(set));
    for (const std::string& path : paths) {
        // A path the process loaded already adds nothing twice.
        if (std::any_of(components->sets().begin(), components->sets().end(),
                        [&](const auto& set) { return set->source == path; }))
            continue;
        try {
            components->add(load_plugin_library(path));
        } catch (const Error& e) {
            throw Error(e.status(), std::string("option \"plugins\": ") + e.what());
        }
    }
    return components;
}

}  // namespace structmd::api

using namespace structmd;
using namespace structmd::api;

extern "C" {

structmd_status structmd_load_plugin(const char* path) {
    return guarded(thread_error(), [&] {
        require_pointer(path, "path");
        LoadedPlugins& loaded = process_plugins();
        std::lock_guard<std::mutex> lock(loaded.mutex);
        for (const auto& set : loaded.sets)
            if (set->source == path) return;  // loaded already: nothing to do
        auto set = load_plugin_library(path);
        // Its names must be new beside the built-ins and every plugin loaded before.
        ForceFieldComponents check;
        for (const auto& other : loaded.sets) check.add(other);
        check.add(set);
        loaded.sets.push_back(std::move(set));
    });
}

}  // extern "C"
