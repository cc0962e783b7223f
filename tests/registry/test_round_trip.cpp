// registry.round_trip: what the readers store for every registry entry is what the input gave, by
// name. The spec is read with read_forcefield (read_integrators) from the minimal input of the
// entry's schema and each parameter is compared with the input's value of the same name: pairs row
// by row and the entry's shared values, bonds by decoding their flat values with the spec's schema,
// externals and integrators directly. The order in which the input lists labels and keys must not
// matter, a parameter with a default must take it when left out, and a required one must be asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/logger.hpp"
#include "forcefield/read_forcefield.hpp"
#include "input/description.hpp"
#include "integrators/read_integrators.hpp"
#include "registry_inputs.hpp"

namespace structmd::registry_test {
namespace {

const Logger kQuiet(LogLevel::quiet, nullptr);

std::vector<ComponentKey> forcefield_keys() { return schema_forcefield_keys(); }

const ForceFieldComponent& component(const ComponentKey& key) {
    const ForceFieldComponent* c = forcefield_registry().find(key);
    if (!c) throw Error(STRUCTMD_ERR_INTERNAL, key.text() + " is not registered");
    return *c;
}

std::vector<std::string> names_of(const std::vector<Parameter>& schema) {
    std::vector<std::string> names;
    for (const Parameter& p : schema) names.push_back(p.name);
    return names;
}

// The column of `label` in an entry's table.
size_t column(const Json& entry, const std::string& label) {
    const Json& labels = entry.at("labels");
    for (size_t k = 0; k < labels.size(); ++k)
        if (labels[k].get<std::string>() == label) return k;
    throw Error(STRUCTMD_ERR_INTERNAL, "the test input has no label " + label);
}

ForceFieldSpec read(const ForceFieldComponent& c, const Json& entry) {
    const input::ParsedDocument parsed = input::parse_document(document_with(c, entry).dump());
    return read_forcefield(parsed.system, kQuiet);
}

// Every parameter of the spec's one interaction equals, by name, the input entry's.
void expect_values_of_input(const ForceFieldComponent& c, const Json& entry, const ForceFieldSpec& spec) {
    ASSERT_EQ(spec.pairs.size() + spec.bonds.size() + spec.externals.size(), 1u);
    const Json parameters = entry.value("parameters", Json::object());
    switch (c.kind) {
        case InteractionKind::pair: {
            ASSERT_EQ(spec.pairs.size(), 1u);
            const PairSpec& pair = spec.pairs[0];
            EXPECT_EQ(pair.key, c.key);
            if (c.readsCutOffFactor)
                EXPECT_EQ(pair.cutOffFactor, parameters.at("cutOffFactor").get<double>());
            EXPECT_EQ(pair.shared.all().size(), c.entryParameters.size()) << "shared values beyond the schema";
            for (const Parameter& p : c.entryParameters)
                EXPECT_EQ(pair.shared.vector(p.name), numbers_of(parameters.at(p.name))) << "shared " << p.name;
            if (c.parameters.empty()) {
                EXPECT_TRUE(pair.rows.empty());
                break;
            }
            const Json& data = entry.at("data");
            ASSERT_EQ(pair.rows.size(), data.size());
            const std::vector<std::string> types = {"A", "B"};
            for (size_t r = 0; r < data.size(); ++r) {
                const PairSpec::Row& row = pair.rows[r];
                EXPECT_EQ(types.at(row.typeI), data[r][column(entry, "name_i")].get<std::string>()) << "row " << r;
                EXPECT_EQ(types.at(row.typeJ), data[r][column(entry, "name_j")].get<std::string>()) << "row " << r;
                EXPECT_EQ(row.values.all().size(), c.parameters.size()) << "row " << r << " holds values beyond the schema";
                for (const Parameter& p : c.parameters)
                    EXPECT_EQ(row.values.vector(p.name), numbers_of(data[r][column(entry, p.name)]))
                        << "row " << r << ", " << p.name;
            }
            break;
        }
        case InteractionKind::bond: {
            ASSERT_EQ(spec.bonds.size(), 1u);
            const BondSpec& bonds = spec.bonds[0];
            EXPECT_EQ(bonds.key, c.key);
            EXPECT_EQ(bonds.arity, c.arity);
            EXPECT_EQ(names_of(bonds.schema), names_of(c.parameters)) << "the spec's schema is not the registry's";
            const Json& data = entry.at("data");
            const size_t width = static_cast<size_t>(width_of(bonds.schema));
            ASSERT_EQ(bonds.members.size(), data.size() * c.arity);
            ASSERT_EQ(bonds.values.size(), data.size() * width);
            static const char* const ids[] = {"id_i", "id_j", "id_k", "id_l"};
            for (size_t b = 0; b < data.size(); ++b) {
                for (int m = 0; m < c.arity; ++m)
                    EXPECT_EQ(bonds.members[b * c.arity + m], data[b][column(entry, ids[m])].get<int>())
                        << "bond " << b << ", " << ids[m];
                const ParameterValues values = values_in_order(bonds.schema, &bonds.values[b * width]);
                for (const Parameter& p : c.parameters) {
                    const Json& given = is_common(c, p) ? parameters.at(p.name) : data[b][column(entry, p.name)];
                    EXPECT_EQ(values.vector(p.name), numbers_of(given)) << "bond " << b << ", " << p.name;
                }
            }
            break;
        }
        case InteractionKind::external: {
            ASSERT_EQ(spec.externals.size(), 1u);
            const ExternalSpec& external = spec.externals[0];
            EXPECT_EQ(external.key, c.key);
            EXPECT_EQ(external.values.all().size(), c.parameters.size()) << "values beyond the schema";
            for (const Parameter& p : c.parameters)
                EXPECT_EQ(external.values.vector(p.name), numbers_of(parameters.at(p.name))) << p.name;
            EXPECT_EQ(external.perType, !c.typeParameters.empty());
            if (!external.perType) break;
            const Json& data = entry.at("data");
            ASSERT_EQ(external.rows.size(), data.size());
            for (size_t r = 0; r < data.size(); ++r) {
                const ExternalSpec::Row& row = external.rows[r];
                EXPECT_EQ(type_names().at(row.type), data[r][column(entry, "name")].get<std::string>()) << "row " << r;
                EXPECT_EQ(row.values.all().size(), c.typeParameters.size())
                    << "row " << r << " holds values beyond the schema";
                for (const Parameter& p : c.typeParameters)
                    EXPECT_EQ(row.values.vector(p.name), numbers_of(data[r][column(entry, p.name)]))
                        << "row " << r << ", " << p.name;
            }
            break;
        }
    }
}

// The entry with its labels (and every data row's cells) and its parameters' keys in reverse order.
Json reordered(const Json& entry) {
    Json out = entry;
    if (entry.contains("parameters")) {
        Json parameters = Json::object();
        const Json& given = entry.at("parameters");
        std::vector<std::string> keys;
        for (auto it = given.begin(); it != given.end(); ++it) keys.push_back(it.key());
        std::reverse(keys.begin(), keys.end());
        for (const std::string& key : keys) parameters[key] = given.at(key);
        out["parameters"] = parameters;
    }
    if (entry.contains("labels")) {
        Json labels = entry.at("labels");
        std::reverse(labels.begin(), labels.end());
        out["labels"] = labels;
        for (Json& row : out["data"]) std::reverse(row.begin(), row.end());
    }
    return out;
}

class ForceFieldRoundTrip : public ::testing::TestWithParam<ComponentKey> {};

TEST_P(ForceFieldRoundTrip, EveryParameterReadsBackByName) {
    const ForceFieldComponent& c = component(GetParam());
    const Json entry = forcefield_entry(c);
    ForceFieldSpec spec;
    ASSERT_NO_THROW(spec = read(c, entry));
    expect_values_of_input(c, entry, spec);
}

// The reader finds columns and keys by name: listing them in another order changes nothing, down to
// the layout of a bond's flat values, which follows the component's schema and not the table.
TEST_P(ForceFieldRoundTrip, LabelAndKeyOrderDoNotMatter) {
    const ForceFieldComponent& c = component(GetParam());
    const Json entry = forcefield_entry(c);
    const Json other = reordered(entry);
    if (entry.dump() == other.dump()) return;  // a single key and no table: nothing to reorder
    ForceFieldSpec given, reversed;
    ASSERT_NO_THROW(given = read(c, entry));
    ASSERT_NO_THROW(reversed = read(c, other));
    expect_values_of_input(c, other, reversed);
    if (c.kind == InteractionKind::bond) {
        ASSERT_EQ(given.bonds.size(), 1u);
        ASSERT_EQ(reversed.bonds.size(), 1u);
        EXPECT_EQ(given.bonds[0].values, reversed.bonds[0].values);
        EXPECT_EQ(given.bonds[0].members, reversed.bonds[0].members);
    }
}

INSTANTIATE_TEST_SUITE_P(Registry, ForceFieldRoundTrip, ::testing::ValuesIn(forcefield_keys()),
                         [](const auto& info) { return test_name(info.param); });

// The schema's parameters given once ("parameters": externals, a pair entry's shared values, the
// Common_ bond values) and whether each is required.
std::vector<Parameter> given_once(const ForceFieldComponent& c) {
    switch (c.kind) {
        case InteractionKind::pair: return c.entryParameters;
        case InteractionKind::external: return c.parameters;
        case InteractionKind::bond: {
            std::vector<Parameter> common;
            for (const Parameter& p : c.parameters)
                if (is_common(c, p)) common.push_back(p);
            return common;
        }
    }
    return {};
}

// The numbers the spec holds for the parameter `name` of its one interaction (the first row or bond).
std::vector<double> held(const ForceFieldSpec& spec, const std::string& name) {
    if (!spec.pairs.empty()) return spec.pairs[0].shared.vector(name);
    if (!spec.externals.empty()) return spec.externals[0].values.vector(name);
    const BondSpec& bonds = spec.bonds.at(0);
    return values_in_order(bonds.schema, bonds.values.data()).vector(name);
}

// Leaving out a parameter that has a default gives the default; leaving out a required one (a key of
// "parameters" or a table column) is an input error that names it.
TEST(ForceFieldRoundTripDefaults, OmittedParametersTakeTheirDefaultOrAreAskedFor) {
    int defaults = 0, required = 0;
    for (const ForceFieldComponent& c : forcefield_registry().entries()) {
        if (c.configure) continue;  // no schema before its entry is read (tests/forcefield_expression)
        SCOPED_TRACE(c.key.text());
        const Json entry = forcefield_entry(c);
        for (const Parameter& p : given_once(c)) {
            SCOPED_TRACE(p.name);
            Json without = entry;
            without["parameters"].erase(p.name);
            if (p.required()) {
                ++required;
                try {
                    read(c, without);
                    ADD_FAILURE() << "read without the required parameter";
                } catch (const Error& e) {
                    EXPECT_EQ(e.status(), STRUCTMD_ERR_INPUT) << e.what();
                    EXPECT_NE(std::string(e.what()).find(std::string("parameters.") + p.name), std::string::npos) << e.what();
                }
            } else {
                ++defaults;
                ForceFieldSpec spec;
                ASSERT_NO_THROW(spec = read(c, without));
                EXPECT_EQ(held(spec, p.name), std::vector<double>(p.size, p.fallback));
            }
        }
        if (!entry.contains("labels") || c.kind == InteractionKind::pair) continue;
        for (const Parameter& p : c.kind == InteractionKind::external ? c.typeParameters : c.parameters) {
            if (is_common(c, p)) continue;
            SCOPED_TRACE(std::string("column ") + p.name);
            Json without = entry;
            const size_t col = column(entry, p.name);
            without["labels"].erase(col);
            for (Json& row : without["data"]) row.erase(col);
            ++required;
            try {
                read(c, without);
                ADD_FAILURE() << "read without the column of a parameter";
            } catch (const Error& e) {
                EXPECT_EQ(e.status(), STRUCTMD_ERR_INPUT) << e.what();
                EXPECT_NE(std::string(e.what()).find(p.name), std::string::npos) << e.what();
            }
        }
    }
    EXPECT_GT(defaults, 0) << "no parameter with a default was exercised";
    EXPECT_GT(required, 0);
}

// The integrators' own parameters, likewise by name.
TEST(IntegratorRoundTrip, EveryParameterReadsBackByName) {
    for (const IntegratorComponent& c : integrator_registry().entries()) {
        SCOPED_TRACE(c.key.text());
        const Json entry = integrator_entry(c);
        const input::ParsedDocument parsed = input::parse_document(document(Json::object(), entry).dump());
        std::vector<ScheduleStage> schedule;
        std::vector<IntegratorSpec> specs;
        ASSERT_NO_THROW(specs = read_integrators(parsed.system, {}, schedule));
        ASSERT_EQ(specs.size(), 1u);
        EXPECT_EQ(specs[0].key, c.key);
        EXPECT_EQ(specs[0].parameters.all().size(), c.parameters.size() + c.textOptions.size())
            << "values beyond the schema";
        for (const Parameter& p : c.parameters)
            EXPECT_EQ(specs[0].parameters.vector(p.name), numbers_of(entry.at("parameters").at(p.name))) << p.name;
        // A named choice reads back as the index of the given name among the supported ones.
        for (const TextOption& option : c.textOptions) {
            const auto given = std::find(option.supported.begin(), option.supported.end(),
                                         entry.at("parameters").at(option.name).get<std::string>());
            ASSERT_NE(given, option.supported.end()) << option.name;
            EXPECT_EQ(specs[0].parameters[option.name], static_cast<double>(given - option.supported.begin()))
                << option.name;
        }
    }
}

}  // namespace
}  // namespace structmd::registry_test
