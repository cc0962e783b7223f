// Reading ["External","ConstantTorque"]: one vector, "constantTorque", in the entry's "parameters".
#include "forcefield/constant_torque.hpp"

#include "forcefield/component_registry.hpp"

namespace structmd {

ForceFieldComponent ConstantTorqueComponent::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.parameters = {numbers("constantTorque", 3, "energy")};
    return c;
}

}  // namespace structmd
