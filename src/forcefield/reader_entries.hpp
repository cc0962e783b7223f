#pragma once
// The reader's visitor of a force-field component list (components.hpp): what the input reader
// knows of each component, added to a registry. The built-in registry (component_registry.cpp) and
// plugins (engines/plugin.hpp) both add their components through it, so a plugin's potential is read
// exactly as a built-in one is.
#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/external_potential.hpp"

namespace structmd {

// Whether a functor declares `static constexpr bool under_domains = true` (pair_potential.hpp,
// bond_potential.hpp); the domain check asks the registry, never a list of names.
template <class Potential, class = void>
struct runs_under_domains : std::false_type {};
template <class Potential>
struct runs_under_domains<Potential, std::void_t<decltype(Potential::under_domains)>>
    : std::bool_constant<Potential::under_domains> {};

struct ReaderEntries {
    Registry<ForceFieldComponent>& registry;

    template <class Potential>
    void pair(ComponentKey key) {
        ForceFieldComponent c = component(std::move(key), InteractionKind::pair, Potential::pair_parameters());
        c.entryParameters = Potential::entry_parameters();
        if constexpr (has_text_options<Potential>::value) c.textOptions = Potential::text_options();
        c.units = required_units_of<Potential>();
        c.underDomains = runs_under_domains<Potential>::value;
        c.actingCutoff = [](const ParameterValues& v, const Constants& constants, double cutOffFactor, bool shift) {
            return std::sqrt(static_cast<double>(
                Potential::template make_pair_params<double>(v, constants, cutOffFactor, shift).cutoff2));
        };
        if constexpr (has_cutoff_key<Potential>::value) {
            c.readsCutOffFactor = false;
            c.cutoffKey = Potential::cutoff_key;
        }
        c.overAllPairs = true;
        if constexpr (has_infinite_range<Potential>::value) {
            c.infiniteRange = true;
            c.readsCutOffFactor = false;
            c.takesShift = false;
        }
        if constexpr (acts_on_unlisted_pairs<Potential>::value)
            c.unlistedCutoff = [](const ParameterValues& v, const Constants& constants, double cutOffFactor, bool shift) {
                return std::sqrt(static_cast<double>(
                    Potential::template make_unlisted_pair_params<double>(v, constants, cutOffFactor, shift).cutoff2));
            };
        registry.add(std::move(c));
    }

    template <class Potential>
    void bond(ComponentKey key, std::vector<std::string> common = {}) {
        ForceFieldComponent c = component(std::move(key), InteractionKind::bond, Potential::parameters());
        c.arity = Potential::arity;
        c.units = required_units_of<Potential>();
        c.underDomains = runs_under_domains<Potential>::value;
        for (const std::string& name : common)
            if (std::none_of(c.parameters.begin(), c.parameters.end(),
                             [&](const Parameter& p) { return name == p.name; }))
                throw Error(STRUCTMD_ERR_INTERNAL, c.key.text() + ": common parameter '" + name + "' is not declared");
        c.common = std::move(common);
        registry.add(std::move(c));
    }

    template <class Potential>
    void external(ComponentKey key) {
        ForceFieldComponent c = component(std::move(key), InteractionKind::external, Potential::parameters());
        c.units = required_units_of<Potential>();
        if constexpr (has_type_parameters<Potential>::value) c.typeParameters = Potential::type_parameters();
        if constexpr (has_ignored_type_columns<Potential>::value)
            c.ignoredTypeColumns = Potential::ignored_type_columns();
        registry.add(std::move(c));
    }

    template <class Component>
    void configurable(ComponentKey key) {
        registry.add(Component::reader_entry(std::move(key)));
    }

private:
    static ForceFieldComponent component(ComponentKey key, InteractionKind kind, std::vector<Parameter> parameters) {
        ForceFieldComponent c;
        c.key = std::move(key);
        c.kind = kind;
        c.parameters = std::move(parameters);
        return c;
    }
};

}  // namespace structmd
