// Reading ["External","ExternalTabulated"] and ["External","PolarizationTabulated"] (tabulated_field.hpp):
// the grid's size from "parameters" (nx, ny, nz, scale; the optional dielectricConstant of the
// polarization field) and its cells from the entry's table (i, j, k, energy, and optionally force), every cell given
// exactly once. The force column, which UAMMD-structured interpolates, is checked but not used: the
// force is the gradient of the interpolated energy.
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/tabulated_field.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;
using input::TrackedNode;

namespace {

std::vector<Parameter> field_parameters(bool polarization) {
    std::vector<Parameter> p = {number("nx", "1", Must::be_positive_integer), number("ny", "1", Must::be_positive_integer),
                                number("nz", "1", Must::be_positive_integer), with_default(number("scale", "1"), 1.0)};
    // Optional: UAMMD-structured's current source scales the table by the polarizability alone, and
    // its generators write no dielectricConstant. The fallback 0, which no input may give (it must
    // be positive), stands for "absent".
    if (polarization) p.push_back(with_default(number("dielectricConstant", "1", Must::be_positive), 0.0));
    return p;
}

ForceFieldComponent configure(const ForceFieldComponent& c, bool polarization, const ComponentEntry& entry,
                              const SystemDescription& system) {
    const ParameterValues values = input::read_parameters(entry.node, c.parameters);
    auto config = std::make_shared<TabulatedFieldConfig>();
    const char* const axes[3] = {"nx", "ny", "nz"};
    size_t cells = 1;
    for (int a = 0; a < 3; ++a) {
        config->n[a] = static_cast<int>(values[axes[a]]);
        cells *= static_cast<size_t>(config->n[a]);
    }
    if (cells > (size_t{1} << 28))
        throw input_error(entry.node.path() + ".parameters", "the grid has " + std::to_string(cells) +
                                                                 " cells, more than 2^28");
    const double scale = values["scale"];
    const input::Table table = input::read_table(entry.node, {"i", "j", "k", "energy"}, {"force"});
    if (table.rows() != cells)
        throw input_error(entry.node.path() + ".data", "expected one row per cell, nx ny nz = " + std::to_string(cells) +
                                                           ", got " + std::to_string(table.rows()));
    config->energy.assign(cells, 0.0);
    std::vector<uint8_t> given(cells, 0);
    const char* const labels[3] = {"i", "j", "k"};
    for (size_t row = 0; row < table.rows(); ++row) {
        int index[3];
        for (int a = 0; a < 3; ++a) {
            const TrackedNode cell = table.cell(row, labels[a]);
            const int64_t value = cell.as<int64_t>();
            if (value < 0 || value >= config->n[a])
                throw input_error(cell.path(), std::string("cell index ") + std::to_string(value) + " is outside 0.." +
                                                   std::to_string(config->n[a] - 1) + " (" + axes[a] + " = " +
                                                   std::to_string(config->n[a]) + ")");
            index[a] = static_cast<int>(value);
        }
        const size_t at = index[0] + config->n[0] * (index[1] + static_cast<size_t>(config->n[1]) * index[2]);
        if (given[at]) throw input_error(table.row(row).path(), "this cell is listed twice");
        given[at] = 1;
        config->energy[at] = scale * input::read_parameter(table.cell(row, "energy"), number("energy", "energy"))[0];
        if (table.has("force")) input::read_parameter(table.cell(row, "force"), numbers("force", 3, "energy/length"));
    }
    if (polarization) {
        const std::vector<double>& polarizability = system.stateColumns[StateColumn::polarizability];
        if (polarizability.empty())
            throw input_error(entry.node.path() + ".type", c.key.text() +
                                                               " scales the field by each particle's polarizability: "
                                                               "the state needs a \"polarizability\" column");
        const double dielectricConstant = values["dielectricConstant"];
        const double eps =
            dielectricConstant > 0.0 ? dielectricConstant / (4.0 * M_PI * system.units.electricConversion) : 1.0;
        for (double alpha : polarizability) config->factor.push_back(eps * alpha);
    }
    ForceFieldComponent configured = c;
    configured.config = config;
    return configured;
}

}  // namespace

template <bool Polarization>
ForceFieldComponent TabulatedFieldComponent<Polarization>::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.parameters = field_parameters(Polarization);
    c.configure = [c](const ComponentEntry& entry, const SystemDescription& system) {
        return configure(c, Polarization, entry, system);
    };
    return c;
}

template struct TabulatedFieldComponent<false>;
template struct TabulatedFieldComponent<true>;

}  // namespace structmd
