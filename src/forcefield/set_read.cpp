// Reading the Set1 and Set2 components (set_interaction.hpp): the entry's table gives per row its
// sets of particle ids ("idSet_i", and "idSet_j" for Set2) and the potential's row parameters; the
// entry's "parameters" those given once (the Common_ variants), read as an External's are.
#include <map>
#include <string>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/set_interaction.hpp"
#include "forcefield/set_table_read.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;
using input::TrackedNode;

namespace {

const char* const kSetLabels[] = {"idSet_i", "idSet_j"};

}  // namespace

std::shared_ptr<SetConfig> read_set_table(const ComponentEntry& entry, const SystemDescription& system,
                                          const std::vector<std::string>& setLabels,
                                          const std::vector<Parameter>& schema) {
    std::vector<std::string> required = setLabels, optional;
    for (const Parameter& p : schema) (p.required() ? required : optional).push_back(p.name);
    const input::Table table = input::read_table(entry.node, required, optional);
    auto config = std::make_shared<SetConfig>();
    config->sets = static_cast<int>(setLabels.size());
    config->schema = schema;
    config->start.push_back(0);
    const int64_t n = system.numParticles();
    // Each particle in one set of the entry at most (as UAMMD-structured requires): the members'
    // threads then never write one particle twice.
    std::map<int64_t, std::string> seen;
    for (size_t r = 0; r < table.rows(); ++r) {
        for (const std::string& label : setLabels) {
            const TrackedNode list = table.cell(r, label);
            if (!list.is_array() || list.size() == 0)
                throw input_error(list.path(), "expected a non-empty list of particle ids");
            for (size_t k = 0; k < list.size(); ++k) {
                const TrackedNode cell = list.at(k);
                const int64_t id = cell.as<int64_t>();
                if (id < 0 || id >= n)
                    throw input_error(cell.path(), "particle id " + std::to_string(id) +
                                                       " does not exist (ids are 0.." + std::to_string(n - 1) + ")");
                const auto [at, inserted] = seen.emplace(id, cell.path());
                if (!inserted)
                    throw input_error(cell.path(), "particle " + std::to_string(id) + " is already in a set of this entry (" +
                                                       at->second + "); the sets must not overlap");
                config->members.push_back(static_cast<int>(id));
            }
            config->start.push_back(static_cast<int>(config->members.size()));
        }
        for (const Parameter& p : schema) {
            const std::vector<double> numbers = table.has(p.name) ? input::read_parameter(table.cell(r, p.name), p)
                                                                  : std::vector<double>(p.size, p.fallback);
            config->values.insert(config->values.end(), numbers.begin(), numbers.end());
        }
    }
    return config;
}

namespace {

template <class Potential>
ForceFieldComponent set_reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.arity = Potential::arity;
    c.parameters = set_entry_parameters<Potential>::get();
    const std::vector<Parameter> schema = Potential::parameters();
    c.configure = [c, schema](const ComponentEntry& entry, const SystemDescription& system) {
        ForceFieldComponent configured = c;
        configured.config = read_set_table(
            entry, system, std::vector<std::string>(kSetLabels, kSetLabels + Potential::arity), schema);
        return configured;
    };
    return c;
}

}  // namespace

template <class Potential>
ForceFieldComponent SetComponent<Potential>::reader_entry(ComponentKey key) {
    return set_reader_entry<Potential>(std::move(key));
}

template ForceFieldComponent SetComponent<ConstantForceBond>::reader_entry(ComponentKey);
template ForceFieldComponent SetComponent<FixedHarmonicAnisotropic>::reader_entry(ComponentKey);
template ForceFieldComponent SetComponent<FixedHarmonicIsotropicCommon>::reader_entry(ComponentKey);
template ForceFieldComponent SetComponent<ConstantTorqueOnSet>::reader_entry(ComponentKey);
template ForceFieldComponent SetComponent<RadialBond<ConstantForceRadial>>::reader_entry(ComponentKey);
template ForceFieldComponent SetComponent<RadialBond<HarmonicBond>>::reader_entry(ComponentKey);
template ForceFieldComponent SetComponent<ConstantTorqueBetweenSets>::reader_entry(ComponentKey);

}  // namespace structmd
