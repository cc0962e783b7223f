#include "forcefield/component_registry.hpp"

#include "core/error.hpp"
#include "forcefield/components.hpp"
#include "forcefield/reader_entries.hpp"

namespace structmd {

const Registry<ForceFieldComponent>& forcefield_registry() {
    static const Registry<ForceFieldComponent> builtin = [] {
        Registry<ForceFieldComponent> registry;
        ReaderEntries entries{registry};
        visit_builtin_forcefield(entries);
        return registry;
    }();
    return builtin;
}

void require_orientations(const ForceFieldComponent& c, const input::ComponentEntry& entry,
                          const input::SystemDescription& system, const std::string& use) {
    if (system.orientations.empty())
        throw input_error(entry.node.path() + ".type",
                          c.key.text() + " " + use + ": the state needs a \"direction\" column");
}

}  // namespace structmd
