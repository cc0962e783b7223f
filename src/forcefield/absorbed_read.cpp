// Reading ["Surface","Absorbed"] (absorbed.hpp): K and heightThreshold from "parameters", and the
// particles below the threshold, with their positions, from the state.
#include "forcefield/absorbed.hpp"

#include "forcefield/component_registry.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

ForceFieldComponent AbsorbedComponent::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.parameters = {number("K", "energy/length^2"), number("heightThreshold", "length")};
    c.configure = [c](const input::ComponentEntry& entry, const input::SystemDescription& system) {
        const ParameterValues values = input::read_parameters(entry.node, c.parameters);
        auto config = std::make_shared<AbsorbedConfig>();
        config->K = values["K"];
        const double threshold = values["heightThreshold"];
        for (size_t id = 0; id < system.positions.size(); ++id) {
            const auto& p = system.positions[id];
            if (!(p[2] < threshold)) continue;
            config->ids.push_back(static_cast<int>(id));
            config->anchors.push_back({p[0], p[1], p[2]});
        }
        ForceFieldComponent configured = c;
        configured.config = config;
        return configured;
    };
    return c;
}

}  // namespace structmd
