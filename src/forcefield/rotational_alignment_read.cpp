// Reading ["Bond2","RAP"] and ["Bond2","HarmonicRAP"]: bonds as every Bond2 entry (read_forcefield.cpp),
// once the entry is checked against what the potential needs: the state's orientations (its
// "direction" column) and a target quaternion R of unit norm in every bond.
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/rotational_alignment.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

namespace {

ForceFieldComponent configure(const ForceFieldComponent& c, const input::ComponentEntry& entry,
                              const input::SystemDescription& system) {
    require_orientations(c, entry, system, "aligns the particles' orientations");
    std::vector<std::string> columns = {"id_i", "id_j"};
    for (const Parameter& p : c.parameters) columns.push_back(p.name);
    const input::Table table = input::read_table(entry.node, columns);
    for (size_t row = 0; row < table.rows(); ++row) {
        const input::TrackedNode cell = table.cell(row, "R");
        const std::vector<double> q = input::read_parameter(cell, numbers("R", 4, "1"));
        const double norm2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
        // The tolerance of the state's directions: the digits a generator prints.
        if (!(std::abs(norm2 - 1.0) < 1e-4))
            throw input_error(cell.path(), "expected a unit quaternion [q0, q1, q2, q3], got norm^2 = " +
                                               std::to_string(norm2));
    }
    return c;
}

}  // namespace

template <class Potential>
ForceFieldComponent OrientedBondComponent<Potential>::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::bond;
    c.arity = Potential::arity;
    c.parameters = Potential::parameters();
    c.configure = [c](const input::ComponentEntry& entry, const input::SystemDescription& system) {
        return configure(c, entry, system);
    };
    return c;
}

template struct OrientedBondComponent<RAPPotential>;
template struct OrientedBondComponent<HarmonicRAPPotential>;

}  // namespace structmd
