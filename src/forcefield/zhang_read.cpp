// Reading ["NonBonded","Zhang"] (zhang.hpp): a pair entry read as every NonBonded one, its
// per-type-pair table (radius, epsilon, mu, chi, theta) setting each pair's range r_c = 5.2 radius (no
// cutOffFactor), once the entry is checked against what it needs: the state's orientations and, in
// "parameters", an optional body axis of unit length.
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/zhang.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

namespace {

ForceFieldComponent configure(const ForceFieldComponent& c, const input::ComponentEntry& entry,
                              const input::SystemDescription& system) {
    require_orientations(c, entry, system, "orients each particle by its direction");
    auto config = std::make_shared<ZhangConfig>();
    const input::TrackedNode params = input::parameters_of(entry.node);
    if (params.valid())
        if (const auto axis = params.find("axis")) {
            const std::vector<double> a = input::read_parameter(*axis, numbers("axis", 3, "1"));
            const double length = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
            // UAMMD-structured's rule: a unit vector, to 1e-6.
            if (!(std::abs(length - 1.0) < 1e-6))
                throw input_error(axis->path(), "the axis must be a unit vector, got length " + std::to_string(length));
            config->axis = {a[0] / length, a[1] / length, a[2] / length};
        }
    ForceFieldComponent configured = c;
    configured.config = config;
    return configured;
}

}  // namespace

ForceFieldComponent ZhangComponent::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::pair;
    c.parameters = ZhangPotential::pair_parameters();
    c.readsCutOffFactor = false;
    c.cutoffKey = "data";
    c.actingCutoff = [](const ParameterValues& v, const Constants&, double, bool) {
        return std::sqrt(static_cast<double>(ZhangPotential::make_params<double>(v).cutoff2));
    };
    c.configure = [c](const input::ComponentEntry& entry, const input::SystemDescription& system) {
        return configure(c, entry, system);
    };
    return c;
}

}  // namespace structmd
