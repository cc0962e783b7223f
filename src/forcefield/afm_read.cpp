// Reading ["AFM","SphericalTip"] (afm_tip.hpp) and ["AFM","SphericallyBluntedConicTip"] (afm_conic_tip.hpp): its table (idSet_i: the tip, one particle; idSet_j:
// the sample; the tip's and the chip's values per row) and the time step that moves the chip.
#include <optional>
#include <string>
#include <type_traits>

#include "core/error.hpp"
#include "forcefield/afm_read.hpp"
#include "forcefield/afm_conic_tip.hpp"
#include "forcefield/afm_tip.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/set_table_read.hpp"
#include "input/time_step.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;

namespace {

// UAMMD-structured moves the chip by the fundamental time step, which its integrators set: that of
// the integrator that runs first.
double chip_time_step(const SystemDescription& system, const std::string& path) {
    if (const std::optional<double> timeStep = input::first_time_step(system)) return *timeStep;
    throw input_error(path, "the chip moves by the time step, and the input gives none (the first scheduled "
                            "integrator's timeStep or global.fundamental's)");
}

// A tip whose values have rules beyond their parameters' declares `static std::string check(const
// ParameterValues&)`, the message for a row that breaks them (empty: none).
template <class Tip, class = void>
struct has_row_check : std::false_type {};
template <class Tip>
struct has_row_check<Tip, std::void_t<decltype(Tip::check(std::declval<const ParameterValues&>()))>>
    : std::true_type {};

}  // namespace

std::vector<Parameter> afm_schema(std::vector<Parameter> tip) {
    tip.push_back(number("K", "energy/length^2"));
    tip.push_back(number("Kxy", "energy/length^2"));
    tip.push_back(number("tipVelocity", "length/time"));
    tip.push_back(numbers("startChipPosition", 3, "length"));
    tip.push_back(number("indentationStartStep", "steps", Must::be_non_negative));
    tip.push_back(with_default(number("indentationBackwardStep", "steps", Must::be_non_negative), 0.0));
    return tip;
}

template <class Tip>
ForceFieldComponent AfmComponent<Tip>::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.configure = [c](const ComponentEntry& entry, const SystemDescription& system) {
        const std::vector<Parameter> schema = afm_schema(Tip::parameters());
        const std::shared_ptr<SetConfig> sets = read_set_table(entry, system, {"idSet_i", "idSet_j"}, schema);
        auto config = std::make_shared<AfmConfig>();
        static_cast<SetConfig&>(*config) = *sets;
        const size_t rows = (config->start.size() - 1) / 2;
        const size_t width = static_cast<size_t>(width_of(schema));
        for (size_t row = 0; row < rows; ++row) {
            const std::string rowPath = entry.node.path() + ".data[" + std::to_string(row) + "]";
            if (config->start[2 * row + 1] - config->start[2 * row] != 1)
                throw input_error(rowPath, "the tip (idSet_i) must be one particle");
            ParameterValues v;
            v.assign(schema, config->values.data() + row * width);
            const double start = v["indentationStartStep"], backward = v["indentationBackwardStep"];
            if (start != static_cast<double>(static_cast<int64_t>(start)) ||
                backward != static_cast<double>(static_cast<int64_t>(backward)))
                throw input_error(rowPath, "indentationStartStep and indentationBackwardStep must be whole steps");
            if (backward > 0.0 && backward < start)
                throw input_error(rowPath, "indentationBackwardStep is before indentationStartStep");
            if constexpr (has_row_check<Tip>::value)
                if (const std::string problem = Tip::check(v); !problem.empty()) throw input_error(rowPath, problem);
        }
        config->timeStep = chip_time_step(system, entry.node.path());
        ForceFieldComponent configured = c;
        configured.config = config;
        return configured;
    };
    return c;
}

template ForceFieldComponent AfmComponent<SphericalTipPotential>::reader_entry(ComponentKey);
template ForceFieldComponent AfmComponent<SphericallyBluntedConicTipPotential>::reader_entry(ComponentKey);

}  // namespace structmd
