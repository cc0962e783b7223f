#include "forcefield/component_registry.hpp"

#include <algorithm>
#include <cmath>

#include "forcefield/components.hpp"

namespace structmd {

namespace {

struct ReaderEntries {
    Registry<ForceFieldComponent> registry;

    template <class Potential>
    void pair(ComponentKey key) {
        ForceFieldComponent c;
        c.key = std::move(key);
        c.kind = InteractionKind::pair;
        c.parameters = Potential::pair_parameters();
        c.entryParameters = Potential::entry_parameters();
        c.actingCutoff = [](const ParameterValues& v, const Constants& constants, double cutOffFactor, bool shift) {
            return std::sqrt(
                static_cast<double>(Potential::template make_pair_params<double>(v, constants, cutOffFactor, shift).cutoff2));
        };
        registry.add(std::move(c));
    }

    template <class Potential>
    void bond(ComponentKey key, std::vector<std::string> common = {}) {
        ForceFieldComponent c;
        c.key = std::move(key);
        c.kind = InteractionKind::bond;
        c.arity = Potential::arity;
        c.parameters = Potential::parameters();
        for (const std::string& name : common)
            if (std::none_of(c.parameters.begin(), c.parameters.end(), [&](const Parameter& p) { return name == p.name; }))
                throw Error(STRUCTMD_ERR_INTERNAL, c.key.text() + ": common parameter '" + name + "' is not declared");
        c.common = std::move(common);
        registry.add(std::move(c));
    }

    template <class Potential>
    void external(ComponentKey key) {
        ForceFieldComponent c;
        c.key = std::move(key);
        c.kind = InteractionKind::external;
        c.parameters = Potential::parameters();
        registry.add(std::move(c));
    }
};

}  // namespace

const Registry<ForceFieldComponent>& forcefield_registry() {
    static const Registry<ForceFieldComponent> builtin = [] {
        ReaderEntries entries;
        visit_builtin_forcefield(entries);
        return std::move(entries.registry);
    }();
    return builtin;
}

}  // namespace structmd
