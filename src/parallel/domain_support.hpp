#pragma once
// What spatial domain decomposition (domains_over_ranks.hpp) supports, checked on the parsed input:
// a component runs under domains when its registry entry says so (`underDomains`, declared by the
// component); anything else is refused by its JSON path, STRUCTMD_ERR_UNSUPPORTED "<path>: <what> is
// not available under domain decomposition".
#include "forcefield/component_registry.hpp"
#include "input/description.hpp"
#include "simulation/simulation_spec.hpp"

namespace structmd {

// `spec` is what read_simulation made of `document`; `components` the registry it read with.
void check_domain_support(const input::ParsedDocument& document, const SimulationSpec& spec,
                          const Registry<ForceFieldComponent>& components);

}  // namespace structmd
