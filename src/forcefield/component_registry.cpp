#include "forcefield/component_registry.hpp"

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

}  // namespace structmd
