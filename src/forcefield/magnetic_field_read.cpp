// Reading the magnetic terms. ["External","ConstantMagneticField"] and ["External","ACMagneticField"]:
// the amplitude b0 and the direction, and for the alternating field its frequency and phase, in the
// entry's "parameters"; ["NonBonded","DipolarMagnetic"]: the permeability and its own cutOff, for
// every type pair.
#include "forcefield/component_registry.hpp"
#include "forcefield/dipolar_magnetic.hpp"
#include "forcefield/magnetic_field.hpp"

namespace structmd {

template <bool Alternating>
ForceFieldComponent MagneticFieldComponent<Alternating>::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.needsMagnetization = true;
    c.parameters = {number("b0", "energy/moment"), numbers("direction", 3, "1")};
    if (Alternating)
        c.parameters.insert(c.parameters.end(),
                            {number("frequency", "1/time"), with_default(number("phase", "1"), 0.0)});
    return c;
}

ForceFieldComponent DipolarMagnetic::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::pair;
    c.needsMagnetization = true;
    c.entryParameters = {number("permeability", "field length^3/moment", Must::be_positive),
                         number("cutOff", "length", Must::be_positive)};
    c.readsCutOffFactor = false;
    c.takesShift = false;
    c.actingCutoff = [](const ParameterValues& v, const Constants&, double, bool) { return v["cutOff"]; };
    return c;
}

template ForceFieldComponent MagneticFieldComponent<false>::reader_entry(ComponentKey);
template ForceFieldComponent MagneticFieldComponent<true>::reader_entry(ComponentKey);

}  // namespace structmd
