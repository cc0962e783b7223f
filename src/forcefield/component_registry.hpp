#pragma once
// What the input reader knows of each force-field component: its kind, its parameters by name (with
// units, defaults and rules) and, for pair terms, the distance at which given values stop acting.
// Made from the built-in list (components.hpp); a handle may add components to its own copy.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "core/registry.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/pair_potential.hpp"
#include "input/description.hpp"

namespace structmd {

enum class InteractionKind { pair, bond, external };

struct ForceFieldComponent {
    ComponentKey key;
    InteractionKind kind = InteractionKind::bond;
    int arity = 0;                           // bonds: particles per bond
    std::vector<Parameter> parameters;       // pairs: per type pair; bonds: per bond; externals: the entry's
    std::vector<Parameter> entryParameters;  // pairs: given once in the entry's "parameters"
    std::vector<TextOption> textOptions;     // pairs: named choices in the entry's "parameters"
    // Externals of per-type parameters (the Surface family): the columns of the entry's table, one
    // row per type named by "name", and columns that table may also have but nobody reads; both empty
    // for an external that takes "parameters" only.
    std::vector<Parameter> typeParameters;
    std::vector<std::string> ignoredTypeColumns;
    std::vector<std::string> common;         // bonds: given once for every bond (the Common_ variants)
    // The one unit system the component is defined in (its constants are numbers in those units, as
    // "KcalMol_A"); empty: any. An input in other units is refused, naming the entry's type.
    std::string units;
    // Reads the particles' magnetic moments: the state must give their magnetization.
    bool needsMagnetization = false;
    // Runs under spatial domains (parallel/domains_over_ranks.hpp): reads of a particle only what a
    // domain's ghosts carry. Declared by the functor (`under_domains`) or the configurable's entry.
    bool underDomains = false;
    // Pairs: the largest distance at which the term acts with these values (shared and one row's).
    std::function<double(const ParameterValues&, const Constants&, double cutOffFactor, bool shift)> actingCutoff;
    bool readsCutOffFactor = true;  // pairs: the entry gives "cutOffFactor" (else its own cut-off parameter)
    bool takesShift = true;  // pairs: false for a term without a shifted form, which refuses "shift": true
    // Pairs: the factory can run the term over all pairs (an ["NBody", "all"] list) as well as over a
    // Verlet list; set for the potentials of components.hpp's pair<> (built-in and plugin alike).
    bool overAllPairs = false;
    // Pairs of no cutoff (Coulomb, Gravity): over all pairs only, in a box open along every axis.
    bool infiniteRange = false;
    // Pairs that read no cutOffFactor: the member of the entry that sets the range, for the error of a
    // cutoff too long for the box ("parameters.gamma", "data"; empty: "parameters.cutOff").
    std::string cutoffKey;
    // Pairs whose unlisted type pairs interact (the electrostatics of DLVO): their range, from the
    // shared parameters; null where unlisted type pairs do not interact.
    std::function<double(const ParameterValues&, const Constants&, double cutOffFactor, bool shift)> unlistedCutoff;
    // Pairs whose cutoff is not a parameter (a table's range): the path that sets the largest, for
    // the error of a cutoff too long for the box.
    std::string cutoffPath;

    // A configurable component's parameters depend on its entry (an expression names its own
    // columns; a table reads a file). configure() reads what it needs from the entry and returns the
    // component as configured for it, with `config` set for the engine's factory; input errors name
    // the entry's path.
    std::function<ForceFieldComponent(const input::ComponentEntry&, const input::SystemDescription&)> configure;
    std::shared_ptr<const ComponentConfig> config;
};

const Registry<ForceFieldComponent>& forcefield_registry();

// For a component that reads the particles' orientations: an input error at the entry's type unless
// the state gives them (its "direction" column); `use` says what the component does with them
// ("aligns the particles' orientations").
void require_orientations(const ForceFieldComponent& c, const input::ComponentEntry& entry,
                          const input::SystemDescription& system, const std::string& use);

}  // namespace structmd
