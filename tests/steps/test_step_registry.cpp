// The simulation-step registry walked entry by entry: every registered step loads from a minimal input
// built from its own schema, the shared parameters reach the step it builds, every parameter it
// declares is read (and it reads nothing it does not declare), a missing required parameter or a bad
// value is named by its path, and an unknown step lists the known ones.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "forcefield/component_set.hpp"
#include "forcefield/afm_read.hpp"
#include "forcefield/afm_tip.hpp"
#include "forcefield/patchy_particles.hpp"
#include "input/description.hpp"
#include "steps/read_simulation_steps.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {
namespace {

using nlohmann::json;

const std::string kEntry = "s";  // the one simulationStep entry of each document
const std::string kEntryPath = "simulationStep." + kEntry;
const std::string kParametersPath = kEntryPath + ".parameters";

// Four Lennard-Jones particles in a 10-wide box, with magnetic moments (for the magnetization
// measures and formats); the group "pair" holds particles 1 and 2.
json base_document() {
    return {
        {"system", {{"info", {{"type", {"Simulation", "Information"}}, {"parameters", {{"name", "steps"}}}}}}},
        {"global",
         {{"types",
           {{"type", {"Types", "Basic"}},
            {"labels", {"name", "mass", "radius", "charge"}},
            {"data", {{"A", 1.0, 0.5, 0.0}}}}},
          {"ensemble",
           {{"type", {"Ensemble", "NVT"}},
            {"labels", {"box", "temperature"}},
            {"data", {{{10.0, 10.0, 10.0}, 1.0}}}}}}},
        {"state",
         {{"labels", {"id", "position", "magnetization"}},
          {"data",
           {{0, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0, 1.0}},
            {1, {1.1, 0.0, 0.0}, {0.0, 1.0, 0.0, 1.5}},
            {2, {0.0, 1.1, 0.0}, {0.0, 0.0, 1.0, 0.5}},
            {3, {0.0, 0.0, 1.1}, {0.6, 0.0, 0.8, 2.0}}}}}},
        {"topology", {{"structure", {{"labels", {"id", "type"}}, {"data", {{0, "A"}, {1, "A"}, {2, "A"}, {3, "A"}}}}}}},
        {"integrator",
         {{"vv", {{"type", {"Verlet", "VelocityVerlet"}}, {"parameters", {{"timeStep", 0.001}}}}},
          {"schedule",
           {{"type", {"Schedule", "Integrator"}},
            {"labels", {"order", "integrator", "steps"}},
            {"data", {{1, "vv", 100}}}}}}}};
}

// Groups, an AFM entry (tip 1, sample 0 and 2) for the step that measures one, and dynamically bonded
// patches (a start and an end patch on each particle) for the step that follows their polymers.
ForceFieldSpec with_groups() {
    ForceFieldSpec forceField;
    forceField.groups = {{"pair", {0, 1, 1, 0}}};
    ExternalSpec afm;
    afm.key = {"AFM", "SphericalTip"};
    auto config = std::make_shared<AfmConfig>();
    config->sets = 2;
    config->members = {1, 0, 2};
    config->start = {0, 1, 3};
    config->schema = afm_schema(SphericalTipPotential::parameters());
    config->values = {-1.0, 1.0, 1.0, 10.0, -0.5, 0.0, 0.0, 3.0, 0.0, 0.0};
    config->timeStep = 0.001;
    afm.config = config;
    forceField.externals.push_back(afm);
    ExternalSpec bonding;
    bonding.name = "bonding";
    bonding.key = {"PatchyParticles", "DynamicallyBondedPatchyParticles"};
    auto patches = std::make_shared<PatchyConfig>();
    patches->dynamic = true;
    patches->typeNames = {"S", "E"};
    patches->parent = {0, 0, 1, 1, 2, 2, 3, 3};
    patches->type = {0, 1, 0, 1, 0, 1, 0, 1};
    bonding.config = patches;
    forceField.externals.push_back(bonding);
    return forceField;
}
const ForceFieldSpec kForceField = with_groups();

// The transversers a plugin would register (only what the reader sees of them): "Counted", of no
// parameters, and "Weighted", of a positive "sigma" and two values per particle.
ForceFieldComponents with_transversers() {
    auto set = std::make_shared<ComponentSet>();
    set->source = "test plugin";
    set->transversers.push_back({"Counted", {}, 1});
    set->transversers.push_back({"Weighted", {number("sigma", "length", Must::be_positive)}, 2});
    ForceFieldComponents components;
    components.add(set);
    return components;
}
const ForceFieldComponents kComponents = with_transversers();

std::string output_path() { return (std::filesystem::temp_directory_path() / "structmd_step_registry").string(); }

// A valid value for each parameter: text parameters by name (a new required text parameter needs a
// line here), numbers and integers by their rule. 1 is positive, >= 0 and >= 1, and shorter than
// half the box.
json sample_value(const StepParameter& parameter) {
    static const std::map<std::string, json> text = {
        {"outputFilePath", output_path()}, {"outputFormat", "xyz"}, {"group", "All"}, {"compute", "r < 1.5"},
        {"transverser", "Counted"}};
    switch (parameter.kind) {
        case StepValue::integer: return 1;
        case StepValue::number: return 1.0;
        case StepValue::flag: return true;
        case StepValue::texts: return json::array();
        case StepValue::numbers: return json::array({1.0});
        case StepValue::object: return json::object();
        case StepValue::text: {
            const auto found = text.find(parameter.name);
            if (found == text.end()) {
                ADD_FAILURE() << "no sample value for the text parameter '" << parameter.name << "'";
                return "";
            }
            return found->second;
        }
    }
    return nullptr;
}

// The entry's type with the parameters given, inside the base document.
json document_with(const ComponentKey& key, const json& parameters) {
    json document = base_document();
    document["simulationStep"][kEntry] = {{"type", {key.cls, key.subclass}}, {"parameters", parameters}};
    return document;
}

// As above, with a one-row table for a step that reads one: particle ids 0, 1, ... in its id columns,
// a set's name and its list of ids where it names sets, two disjoint lists for two sets, vectors
// where a region is given by centres, normals and points.
json step_document_with(const SimulationStepEntry& step, const json& parameters) {
    json document = document_with(step.key, parameters);
    if (!step.tableLabels.empty()) {
        json row = json::array();
        for (size_t k = 0; k < step.tableLabels.size(); ++k) {
            const std::string& label = step.tableLabels[k];
            row.push_back(label == "name"                             ? json("set")
                          : label == "id_list" || label == "idSet_i" ? json::array({0, 1})
                          : label == "idSet_j"                       ? json::array({2, 3})
                          : label == "center" || label == "independentVector" ? json::array({0.0, 0.0, 0.0})
                          : label == "normalVector"                  ? json::array({0.0, 0.0, 1.0})
                                                                     : json(k));
        }
        document["simulationStep"][kEntry]["labels"] = step.tableLabels;
        document["simulationStep"][kEntry]["data"] = json::array({row});
    }
    return document;
}

// Every required parameter with a sample value (plus `extra`).
json required_parameters(const SimulationStepEntry& step, const json& extra = json::object()) {
    json parameters = json::object();
    for (const StepParameter& parameter : step.parameters)
        if (parameter.required()) parameters[parameter.name] = sample_value(parameter);
    parameters.update(extra);
    return parameters;
}

// The entry's required parameters, overridden or added to by `extra`, inside the base document.
json step_document(const SimulationStepEntry& step, const json& extra = json::object()) {
    return step_document_with(step, required_parameters(step, extra));
}

struct Loaded {
    input::ParsedDocument parsed;
    std::vector<std::unique_ptr<SimulationStep>> steps;
};

Loaded load(const json& document, const Registry<SimulationStepEntry>& registry = simulation_step_registry(),
            const ForceFieldComponents* components = &kComponents) {
    Loaded loaded;
    loaded.parsed = input::parse_document(document.dump());
    loaded.steps =
        read_simulation_steps(registry, loaded.parsed.system, kForceField, components, Logger(LogLevel::quiet, nullptr));
    return loaded;
}

// The error `load` throws for the document, which must have the status given.
std::string load_error(const json& document, structmd_status status = STRUCTMD_ERR_INPUT,
                       const ForceFieldComponents* components = &kComponents) {
    try {
        load(document, simulation_step_registry(), components);
    } catch (const Error& error) {
        EXPECT_EQ(error.status(), status) << error.what();
        return error.what();
    }
    ADD_FAILURE() << "no error for " << document["simulationStep"].dump();
    return "";
}

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

// Runs the check once per registered step, labelled with its key.
void for_each_step(const std::function<void(const SimulationStepEntry&)>& check) {
    ASSERT_FALSE(simulation_step_registry().entries().empty());
    for (const SimulationStepEntry& step : simulation_step_registry().entries()) {
        SCOPED_TRACE(step.key.text());
        check(step);
    }
}

// How many steps an entry's factory makes: one, or none for an entry that schedules nothing.
size_t steps_made_by(const SimulationStepEntry& step) { return step.schedulesNothing ? 0u : 1u; }

TEST(StepRegistry, EveryStepDeclaresTheSharedParametersAndAFactory) {
    for_each_step([](const SimulationStepEntry& step) {
        EXPECT_NE(step.make, nullptr);
        for (const char* shared : {"intervalStep", "startStep", "endStep", "group"}) {
            bool found = false;
            for (const StepParameter& parameter : step.parameters)
                found = found || parameter.name == std::string(shared);
            EXPECT_TRUE(found) << "does not declare " << shared;
        }
        for (size_t a = 0; a < step.parameters.size(); ++a)
            for (size_t b = a + 1; b < step.parameters.size(); ++b)
                EXPECT_NE(std::string(step.parameters[a].name), step.parameters[b].name) << "declared twice";
    });
}

TEST(StepRegistry, EveryStepLoadsFromItsRequiredParameters) {
    for_each_step([](const SimulationStepEntry& step) {
        const Loaded loaded = load(step_document(step));
        ASSERT_EQ(loaded.steps.size(), steps_made_by(step));
        if (!loaded.steps.empty()) EXPECT_EQ(loaded.steps[0]->name(), kEntry);
        EXPECT_NO_THROW(loaded.parsed.system.simulationSteps.at(0).node.check_all_used());
    });
}

// Every declared parameter given: each must be read (nothing is left unused) and the step must have
// looked up nothing in its parameters that its schema does not declare.
TEST(StepRegistry, EveryStepReadsExactlyWhatItDeclares) {
    for_each_step([](const SimulationStepEntry& step) {
        json parameters = json::object();
        for (const StepParameter& parameter : step.parameters)
            parameters[parameter.name] = parameter.required() ? sample_value(parameter) : parameter.fallback;
        const Loaded loaded = load(step_document_with(step, parameters));
        ASSERT_EQ(loaded.steps.size(), steps_made_by(step));
        EXPECT_NO_THROW(loaded.parsed.system.simulationSteps.at(0).node.check_all_used());
        const auto asked = loaded.parsed.tracking->asked.find(kParametersPath);
        ASSERT_NE(asked, loaded.parsed.tracking->asked.end());
        for (const std::string& key : asked->second) {
            bool declared = false;
            for (const StepParameter& parameter : step.parameters) declared = declared || key == parameter.name;
            EXPECT_TRUE(declared) << "reads '" << key << "', which its schema does not declare";
        }
    });
}

// intervalStep 3, startStep 6, endStep 12: the step is due at 6, 9 and 12 only, so each of the three
// reached the step, in its place.
TEST(StepRegistry, TheSharedParametersReachTheStep) {
    for_each_step([](const SimulationStepEntry& step) {
        const Loaded loaded = load(step_document(step, {{"intervalStep", 3}, {"startStep", 6}, {"endStep", 12}}));
        ASSERT_EQ(loaded.steps.size(), steps_made_by(step));
        if (loaded.steps.empty()) return;
        const SimulationStep& built = *loaded.steps[0];
        for (int64_t s = 0; s <= 18; ++s) EXPECT_EQ(built.due(s), s == 6 || s == 9 || s == 12) << "step " << s;
    });
}

TEST(StepRegistry, EveryMissingRequiredParameterIsNamed) {
    for_each_step([](const SimulationStepEntry& step) {
        size_t required = 0;
        for (const StepParameter& parameter : step.parameters) {
            if (!parameter.required()) continue;
            ++required;
            json parameters = required_parameters(step);
            parameters.erase(parameter.name);
            const std::string what = load_error(step_document_with(step, parameters));
            EXPECT_TRUE(starts_with(what, kParametersPath + "." + parameter.name + ": missing required parameter"))
                << what;
        }
        EXPECT_GE(required, 1u) << "intervalStep at least is required";
    });
}

TEST(StepRegistry, AStepWithoutParametersNamesItsFirstRequiredOne) {
    for_each_step([](const SimulationStepEntry& step) {
        json document = step_document_with(step, json::object());
        document["simulationStep"][kEntry].erase("parameters");
        EXPECT_TRUE(starts_with(load_error(document), kParametersPath + ".intervalStep")) << step.key.text();
    });
}

// A value of the wrong kind for any parameter, and a value breaking the rule of a positive one.
TEST(StepRegistry, BadValuesAreNamedByTheirPath) {
    for_each_step([](const SimulationStepEntry& step) {
        for (const StepParameter& parameter : step.parameters) {
            SCOPED_TRACE(parameter.name);
            const std::string path = kParametersPath + "." + parameter.name;
            const json wrongKind = parameter.kind == StepValue::text ? json(7) : json("seven");
            EXPECT_TRUE(
                starts_with(load_error(step_document(step, {{parameter.name, wrongKind}})), path + ": expected"));
            if (parameter.kind == StepValue::integer)
                EXPECT_TRUE(starts_with(load_error(step_document(step, {{parameter.name, 1.5}})),
                                        path + ": expected an integer"));
            if (parameter.must == Must::be_positive)
                for (const json bad : {json(0), json(-1)})
                    EXPECT_TRUE(starts_with(load_error(step_document(step, {{parameter.name, bad}})),
                                            path + ": expected a positive"));
        }
    });
}

TEST(StepRegistry, AnUnknownGroupIsNamedAndAKnownOneIsTakenOrRefused) {
    for_each_step([](const SimulationStepEntry& step) {
        EXPECT_TRUE(starts_with(load_error(step_document(step, {{"group", "nope"}})),
                                kParametersPath + ".group: no group named 'nope'"));
        // A step that measures the whole system refuses a group, naming it; the others take it.
        try {
            const Loaded loaded = load(step_document(step, {{"group", "pair"}}));
            EXPECT_EQ(loaded.steps.size(), steps_made_by(step));
        } catch (const Error& error) {
            EXPECT_EQ(error.status(), STRUCTMD_ERR_UNSUPPORTED) << error.what();
            EXPECT_TRUE(starts_with(error.what(), kParametersPath + ".group: ")) << error.what();
        }
    });
    const std::string what =
        load_error(document_with({"ThermodynamicMeasure", "ThermodynamicQuantityMeasure"},
                                 {{"intervalStep", 1}, {"outputFilePath", output_path()}, {"group", "pair"}}),
                   STRUCTMD_ERR_UNSUPPORTED);
    EXPECT_TRUE(starts_with(what, kParametersPath + ".group: this step measures the whole system")) << what;
}

TEST(StepRegistry, AnUnknownStepNamesTheNearestKnownOnes) {
    const std::string what = load_error(document_with({"Nope", "Never"}, {{"intervalStep", 1}}));
    EXPECT_TRUE(starts_with(what, kEntryPath + ".type: unknown simulation step [\"Nope\", \"Never\"]")) << what;
    const std::string misspelt =
        load_error(document_with({"ThermodynamicMeasure", "ThermodynamicQuantityMeasur"}, {{"intervalStep", 1}}));
    EXPECT_NE(misspelt.find("nearest known simulation steps: [\"ThermodynamicMeasure\", "
                            "\"ThermodynamicQuantityMeasure\"]"),
              std::string::npos)
        << misspelt;
    // A known class with an unknown subclass is unknown too.
    const std::string subclass = load_error(document_with({"GeometricalMeasure", "Never"}, {{"intervalStep", 1}}));
    EXPECT_TRUE(starts_with(subclass, kEntryPath + ".type: unknown simulation step")) << subclass;
}

// ["TransverserMeasure","Plugin"] checks the transverser against the handle's plugins at load: an
// unknown name is named by its path with the names known, a parameter the transverser does not take
// or one breaking its rule by its path inside transverserParameters; without the handle's
// components (a parallel layout that reads without them) the step is refused as unsupported.
TEST(StepRegistry, APluginTransverserMeasureChecksItsTransverserAtLoad) {
    const ComponentKey plugin{"TransverserMeasure", "Plugin"};
    const auto with = [&](const json& extra) {
        json parameters = {{"intervalStep", 1}, {"outputFilePath", output_path()}, {"transverser", "Weighted"},
                           {"transverserParameters", {{"sigma", 0.5}}}};
        parameters.update(extra);
        return document_with(plugin, parameters);
    };
    EXPECT_EQ(load(with(json::object())).steps.size(), 1u);
    const std::string unknown = load_error(with({{"transverser", "Nope"}}));
    EXPECT_TRUE(starts_with(unknown, kParametersPath + ".transverser: no transverser named 'Nope'")) << unknown;
    EXPECT_NE(unknown.find("'Counted', 'Weighted'"), std::string::npos) << unknown;
    const std::string misspelt = load_error(with({{"transverserParameters", {{"sigma", 0.5}, {"sgma", 1.0}}}}));
    EXPECT_TRUE(starts_with(misspelt, kParametersPath + ".transverserParameters.sgma: unknown parameter (known here: sigma)")) << misspelt;
    const std::string negative = load_error(with({{"transverserParameters", {{"sigma", -1.0}}}}));
    EXPECT_TRUE(starts_with(negative, kParametersPath + ".transverserParameters.sigma: expected a positive")) << negative;
    const std::string missing = load_error(with({{"transverserParameters", json::object()}}));
    EXPECT_TRUE(starts_with(missing, kParametersPath + ".transverserParameters.sigma: missing required")) << missing;
    const std::string none = load_error(with(json::object()), STRUCTMD_ERR_UNSUPPORTED, nullptr);
    EXPECT_TRUE(starts_with(none, kEntryPath + ": [\"TransverserMeasure\",\"Plugin\"]")) << none;
}

TEST(StepRegistry, AStepAddedAtRunTimeLoadsFromItsCopyOnly) {
    struct Probe : SimulationStep {
        using SimulationStep::SimulationStep;
        void run(Simulation&) override {}
    };
    Registry<SimulationStepEntry> registry = simulation_step_registry();
    registry.add({{"Test", "Probe"},
                  step_parameters({{"width", StepValue::number, 2.0, Must::be_positive, "length"}}),
                  [](const StepInput& in) -> std::unique_ptr<SimulationStep> {
                      EXPECT_DOUBLE_EQ(in.parameters.number("width"), 2.0);
                      return std::make_unique<Probe>(in.name, in.interval(), in.start(), in.end());
                  }});
    const json document = document_with({"Test", "Probe"}, {{"intervalStep", 1}});
    EXPECT_EQ(load(document, registry).steps.size(), 1u);
    EXPECT_TRUE(starts_with(load_error(document), kEntryPath + ".type: unknown simulation step"));
    EXPECT_THROW(registry.add({{"Test", "Probe"}, step_parameters({}), nullptr}), Error);
}

// A factory reading a parameter its entry does not declare, or as another kind, is a bug caught at once.
TEST(StepRegistry, ReadingAnUndeclaredParameterIsAnInternalError) {
    Registry<SimulationStepEntry> registry;
    registry.add(
        {{"Test", "Undeclared"}, step_parameters({}), [](const StepInput& in) -> std::unique_ptr<SimulationStep> {
             in.parameters.number("width");
             return nullptr;
         }});
    registry.add(
        {{"Test", "OtherKind"}, step_parameters({}), [](const StepInput& in) -> std::unique_ptr<SimulationStep> {
             in.parameters.text("intervalStep");
             return nullptr;
         }});
    for (const char* subclass : {"Undeclared", "OtherKind"}) {
        try {
            load(document_with({"Test", subclass}, {{"intervalStep", 1}}), registry);
            ADD_FAILURE() << subclass << ": no error";
        } catch (const Error& error) {
            EXPECT_EQ(error.status(), STRUCTMD_ERR_INTERNAL) << error.what();
        }
    }
}

}  // namespace
}  // namespace structmd
