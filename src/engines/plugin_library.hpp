#pragma once
// Loading a plugin library (engines/plugin.hpp says how one is written).
#include <memory>
#include <string>

#include "forcefield/component_set.hpp"

namespace structmd {

// Opens the shared library at `path`, checks its plugin ABI version and build fingerprint against
// this library's, and only then lets it register its components into a new set. The library stays
// mapped for the life of the process (its code runs inside every engine built with its components).
// Throws Error: ERR_IO when the file cannot be opened or is not a loadable library, ERR_ARGUMENT when
// it is not a structmd plugin (no entry points), ERR_UNSUPPORTED when it was built for another plugin
// ABI or another build of structmd, or the status its registration reported.
std::shared_ptr<const ComponentSet> load_plugin_library(const std::string& path);

}  // namespace structmd
