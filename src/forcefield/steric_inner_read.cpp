// Reading ["NonBonded","StericInner6"] and ["NonBonded","StericInner12"] (steric_inner.hpp): a pair
// entry of every type pair (epsilon, cutOffFactor and shift in its "parameters", read as for every
// NonBonded entry) whose sizes come from the state's innerRadius column.
#include <algorithm>
#include <functional>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/steric_inner.hpp"

namespace structmd {

namespace {

ForceFieldComponent configure(const ForceFieldComponent& c, const input::ComponentEntry& entry,
                              const input::SystemDescription& system) {
    const std::vector<double>& innerRadius = system.stateColumns[StateColumn::innerRadius];
    if (innerRadius.empty())
        throw input_error(entry.node.path() + ".type", c.key.text() +
                                                           " sizes each pair by the particles' inner radii: the state "
                                                           "needs an \"innerRadius\" column");
    auto config = std::make_shared<InnerRadiiConfig>();
    config->innerRadius = innerRadius;
    std::vector<double> largest = innerRadius;
    std::sort(largest.begin(), largest.end(), std::greater<double>());
    config->largestSigma = largest[0] + (largest.size() > 1 ? largest[1] : largest[0]);
    ForceFieldComponent configured = c;
    configured.config = config;
    const double largestSigma = config->largestSigma;
    configured.actingCutoff = [largestSigma](const ParameterValues&, const Constants&, double cutOffFactor, bool) {
        return cutOffFactor * largestSigma;
    };
    return configured;
}

}  // namespace

template <int Exponent>
ForceFieldComponent StericInnerComponent<Exponent>::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::pair;
    c.entryParameters = StericInnerPotential<Exponent>::entry_parameters();
    c.actingCutoff = [](const ParameterValues&, const Constants&, double, bool) { return 0.0; };
    c.configure = [c](const input::ComponentEntry& entry, const input::SystemDescription& system) {
        return configure(c, entry, system);
    };
    return c;
}

template struct StericInnerComponent<6>;
template struct StericInnerComponent<12>;

}  // namespace structmd
