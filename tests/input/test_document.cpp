// parse_document on a small valid document and on variations of it that each break one rule of
// spec/input-format.md; every failure must be STRUCTMD_ERR_INPUT and name where it is.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "input/description.hpp"

namespace structmd::input {
namespace {

using nlohmann::json;

// Key order is deliberately not alphabetical, to check that components keep document order.
const char* const kValidDocument = R"({
  // Comments of both kinds are part of the format.
  "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "test", "seed": 42}}},
  "global": {
    /* entries are found by type, not by key */
    "myUnits": {"type": ["Units", "KcalMol_A"]},
    "types": {"type": ["Types", "Basic"], "labels": ["name", "radius", "mass", "charge"],
              "data": [["A", 0.5, 1.0, 0.0], ["B", 1.0, 2.0, -1.0]]},
    "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[10, 20, 30], 300]]},
    "fundamental": {"type": ["Fundamental", "Time"],
                    "parameters": {"currentStep": 5, "simulationTime": 0.5, "timeStep": 0.01}}
  },
  "state": {"labels": ["id", "position", "charge"],
            "data": [[2, [2.0, 2.5, 3.0], 0.5], [0, [0, 0, 0], 0.0], [1, [1, -1, 1], -0.25]]},
  "topology": {
    "structure": {"labels": ["id", "type", "modelId"], "data": [[1, "B", 1], [0, "A", 0], [2, "B", 1]]},
    "forceField": {
      "zbonds": {"type": ["Bond2", "Harmonic"], "parameters": {}, "labels": ["id_i", "id_j", "K", "r0"],
                 "data": [[0, 1, 10, 1]]},
      "lj": {"type": ["NonBonded", "LennardJonesType1"], "parameters": {"condition": "all", "cutOffFactor": 2.5}}
    }
  },
  "integrator": {
    "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
    "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                 "data": [[2, "vv", 10], [1, "bbk", 100]]},
    "bbk": {"type": ["Langevin", "BBK"], "parameters": {"frictionConstant": 1.0}}
  },
  "simulationStep": {"info": {"type": ["UtilsStep", "InfoStep"], "parameters": {"intervalStep": 100}}}
})";

json valid_document() { return json::parse(kValidDocument, nullptr, true, /*ignore_comments=*/true); }

// Stands in for the component readers the engine runs between parse_document and check_all_used.
void consume_components(const ParsedDocument& parsed) {
    for (const auto* section : {&parsed.system.forceField, &parsed.system.integrators, &parsed.system.simulationSteps})
        for (const ComponentEntry& entry : *section) entry.node.mark_used();
}

void expect_input_error_text(const std::string& text, std::initializer_list<std::string> fragments) {
    try {
        parse_document(text);
        FAIL() << "no error was thrown";
    } catch (const Error& error) {
        EXPECT_EQ(error.status(), STRUCTMD_ERR_INPUT) << error.what();
        for (const std::string& fragment : fragments)
            EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos)
                << "message: " << error.what() << "\nexpected to contain: " << fragment;
    }
}

void expect_input_error(const json& document, std::initializer_list<std::string> fragments) {
    expect_input_error_text(document.dump(), fragments);
}

TEST(Document, ValidDocumentGivesTheDescription) {
    const ParsedDocument parsed = parse_document(kValidDocument);
    const SystemDescription& system = parsed.system;
    EXPECT_EQ(system.name, "test");
    EXPECT_EQ(system.seed, 42u);
    EXPECT_EQ(system.units.name, "KcalMol_A");
    EXPECT_DOUBLE_EQ(system.units.boltzmann, 1.987191e-3);
    EXPECT_DOUBLE_EQ(system.units.electricConversion, 332.0716);
    ASSERT_EQ(system.types.size(), 2u);
    EXPECT_EQ(system.types[1].name, "B");
    EXPECT_DOUBLE_EQ(system.types[1].mass, 2.0);
    EXPECT_DOUBLE_EQ(system.types[1].radius, 1.0);
    EXPECT_EQ(system.box, (Vec3d{10, 20, 30}));
    EXPECT_DOUBLE_EQ(system.temperature, 300.0);
    EXPECT_EQ(system.currentStep, 5);
    EXPECT_DOUBLE_EQ(system.simulationTime, 0.5);
    ASSERT_TRUE(system.timeStep.has_value());
    EXPECT_DOUBLE_EQ(*system.timeStep, 0.01);

    ASSERT_EQ(system.numParticles(), 3);
    EXPECT_EQ(system.positions[0], (Vec3d{0, 0, 0}));
    EXPECT_EQ(system.positions[1], (Vec3d{1, -1, 1}));
    EXPECT_EQ(system.positions[2], (Vec3d{2.0, 2.5, 3.0}));
    EXPECT_TRUE(system.velocities.empty());
    EXPECT_EQ(system.typeIndex, (std::vector<int32_t>{0, 1, 1}));
    EXPECT_EQ(system.mass, (std::vector<double>{1.0, 2.0, 2.0}));
    EXPECT_EQ(system.radius, (std::vector<double>{0.5, 1.0, 1.0}));
    EXPECT_EQ(system.charge, (std::vector<double>{0.0, -0.25, 0.5}));  // the state's column overrides the types'
    EXPECT_EQ(system.modelId, (std::vector<int32_t>{0, 1, 1}));
    EXPECT_EQ(system.batchId, (std::vector<int32_t>{0, 0, 0}));
}

TEST(Document, ComponentsKeepDocumentOrderAndTheirNodes) {
    const ParsedDocument parsed = parse_document(kValidDocument);
    const SystemDescription& system = parsed.system;
    ASSERT_EQ(system.forceField.size(), 2u);
    EXPECT_EQ(system.forceField[0].name, "zbonds");
    EXPECT_EQ(system.forceField[1].name, "lj");
    EXPECT_EQ(system.forceField[1].cls, "NonBonded");
    EXPECT_EQ(system.forceField[1].subclass, "LennardJonesType1");
    EXPECT_EQ(system.forceField[1].node.path(), "topology.forceField.lj");
    EXPECT_DOUBLE_EQ(system.forceField[1].node.at("parameters").get<double>("cutOffFactor"), 2.5);

    ASSERT_EQ(system.integrators.size(), 2u);
    EXPECT_EQ(system.integrators[0].name, "vv");
    EXPECT_EQ(system.integrators[1].name, "bbk");
    EXPECT_EQ(system.schedulePath, "integrator.schedule");
    ASSERT_EQ(system.schedule.size(), 2u);
    EXPECT_EQ(system.schedule[0].order, 1);
    EXPECT_EQ(system.schedule[0].integrator, "bbk");
    EXPECT_EQ(system.schedule[0].steps, 100);
    EXPECT_EQ(system.schedule[1].integrator, "vv");

    ASSERT_EQ(system.simulationSteps.size(), 1u);
    EXPECT_EQ(system.simulationSteps[0].cls, "UtilsStep");
}

TEST(Document, EverythingIsUsedOnceComponentsHaveRead) {
    const ParsedDocument parsed = parse_document(kValidDocument);
    consume_components(parsed);
    EXPECT_NO_THROW(parsed.root.check_all_used());
}

TEST(Document, DefaultsWhenOptionalEntriesAreAbsent) {
    json document = valid_document();
    document["system"]["info"]["parameters"].erase("seed");
    document["global"].erase("myUnits");
    document["global"].erase("fundamental");
    document.erase("integrator");
    const SystemDescription system = parse_document(document.dump()).system;
    EXPECT_EQ(system.seed, 0x5EEDu);
    EXPECT_EQ(system.units.name, "None");
    EXPECT_DOUBLE_EQ(system.units.boltzmann, 1.0);
    EXPECT_DOUBLE_EQ(system.units.electricConversion, 1.0);
    EXPECT_EQ(system.currentStep, 0);
    EXPECT_FALSE(system.timeStep.has_value());
    EXPECT_TRUE(system.integrators.empty());
    EXPECT_TRUE(system.schedule.empty());
}

TEST(Document, StateOverridesAndVelocities) {
    json document = valid_document();
    document["state"] = {{"labels", {"id", "position", "velocity", "mass", "radius"}},
                         {"data",
                          {{0, {0, 0, 0}, {1, 2, 3}, 7.0, 0.1},
                           {1, {1, 1, 1}, {0, 0, 0}, 8.0, 0.2},
                           {2, {2, 2, 2}, {-1, 0, 0}, 9.0, 0.3}}}};
    const SystemDescription system = parse_document(document.dump()).system;
    EXPECT_EQ(system.mass, (std::vector<double>{7.0, 8.0, 9.0}));
    EXPECT_EQ(system.radius, (std::vector<double>{0.1, 0.2, 0.3}));
    EXPECT_EQ(system.charge, (std::vector<double>{0.0, -1.0, -1.0}));  // from the types
    ASSERT_EQ(system.velocities.size(), 3u);
    EXPECT_EQ(system.velocities[0], (Vec3d{1, 2, 3}));
}

// UAMMD-structured's orientation and induced-dipole columns (17 of its 72 example inputs have
// "direction"): accepted and checked; the orientations kept, normalised, by particle id.
TEST(Document, StateDirectionPolarizabilityAndInnerRadius) {
    json document = valid_document();
    document["state"] = {{"labels", {"id", "position", "direction", "polarizability", "innerRadius"}},
                         {"data",
                          {{0, {0, 0, 0}, {1, 0, 0, 0}, 0.5, 0.2},
                           {2, {2, 2, 2}, {0.0, 0.0, 0.6, 0.80002}, 1.5, 0.1},
                           {1, {1, 1, 1}, {0.5, 0.5, 0.5, 0.5}, 0.0, 0.0}}}};
    const SystemDescription system = parse_document(document.dump()).system;
    ASSERT_EQ(system.orientations.size(), 3u);
    EXPECT_EQ(system.orientations[1], (std::array<double, 4>{0.5, 0.5, 0.5, 0.5}));
    const double norm = std::sqrt(0.36 + 0.80002 * 0.80002);
    EXPECT_NEAR(system.orientations[2][2], 0.6 / norm, 1e-15);
    EXPECT_NEAR(system.orientations[2][3], 0.80002 / norm, 1e-15);
    document["state"]["data"][1][2] = {0.0, 0.0, 0.6, 0.7};
    expect_input_error(document, {"state.data[1][2]", "unit norm"});
    document["state"]["data"][1][2] = {0.0, 0.6, 0.8};
    expect_input_error(document, {"state.data[1][2]", "quaternion"});
    document["state"]["data"][1][2] = {0.0, 0.0, 0.6, 0.8};
    document["state"]["data"][2][4] = -0.1;
    expect_input_error(document, {"state.data[2][4]", "innerRadius must be >= 0"});
}

// Every optional state column declared in core/state_columns.hpp is read by its label, kept by
// particle id (rows out of order), left empty when absent, and its values checked by its rule.
TEST(Document, EveryDeclaredStateColumn) {
    for (int k = 0; k < kStateColumns; ++k) {
        const StateColumn column = StateColumn(k);
        const StateColumnTraits& c = traits(column);
        SCOPED_TRACE(c.label);
        json document = valid_document();
        document["state"] = {{"labels", {"id", "position", c.label}},
                             {"data", {{2, {2, 2, 2}, 0.5}, {0, {0, 0, 0}, 1.5}, {1, {1, 1, 1}, 2.5}}}};
        const SystemDescription system = parse_document(document.dump()).system;
        EXPECT_EQ(system.stateColumns[column], (std::vector<double>{1.5, 2.5, 0.5}));
        for (int other = 0; other < kStateColumns; ++other)
            if (other != k) EXPECT_TRUE(system.stateColumns[StateColumn(other)].empty());
        document["state"]["data"][1][2] = -1.0;
        if (c.values == ColumnValues::anyNumber) {
            EXPECT_EQ(parse_document(document.dump()).system.stateColumns[column][0], -1.0);
        } else {
            const std::string rule = c.values == ColumnValues::positive ? " must be > 0" : " must be >= 0";
            expect_input_error(document, {"state.data[1][2]", std::string(c.label) + rule});
        }
    }
}

TEST(Document, MalformedJsonGivesLineAndColumn) {
    expect_input_error_text("{\n  \"a\": 1,\n  \"b\": x\n}", {"line 3, column 8: "});
    expect_input_error_text("{\"system\": {}", {"line 1, column 14: "});
}

TEST(Document, ColumnsCountCharactersNotBytes) {
    expect_input_error_text("{\"\xC3\xA9\": x}", {"line 1, column 7: "});
}

TEST(Document, NumberTooLargeForADoubleIsMalformed) {
    expect_input_error_text("{\n\"state\": 1e999}", {"line 2, column 14: ", "number overflow"});
}

TEST(Document, KeyGivenTwiceInOneObject) {
    expect_input_error_text(R"({"topology": {"forceField": {"lj": {}, "lj": {}}}})",
                            {"topology.forceField.lj: given twice in the same object"});
}

TEST(Document, TopLevelMustBeAnObject) { expect_input_error_text("[1, 2]", {"(document): expected an object"}); }

TEST(Document, MissingState) {
    json document = valid_document();
    document.erase("state");
    expect_input_error(document, {"state: missing required entry"});
}

TEST(Document, MissingStructure) {
    json document = valid_document();
    document["topology"].erase("structure");
    expect_input_error(document, {"topology.structure: missing required entry"});
}

TEST(Document, TypeNotInGlobalTypes) {
    json document = valid_document();
    document["topology"]["structure"]["data"][1][1] = "C";
    expect_input_error(document, {"topology.structure.data[1][1]: unknown type 'C' (types are A, B)"});
}

TEST(Document, StateIdTwice) {
    json document = valid_document();
    document["state"]["data"][2][0] = 2;
    expect_input_error(document, {"state.data[2][0]: particle id 2 appears twice (first at state.data[0])"});
}

TEST(Document, StateIdsMustCoverZeroToNMinusOne) {
    json document = valid_document();
    document["state"]["data"][0][0] = 3;
    expect_input_error(document, {"state.data[0][0]: particle id 3 is outside 0..2"});
    document["state"]["data"][0][0] = 1.5;
    expect_input_error(document, {"state.data[0][0]: expected an integer"});
}

TEST(Document, StructureMissingUnknownOrDuplicatedId) {
    json missing = valid_document();
    missing["topology"]["structure"]["data"].erase(2);
    expect_input_error(missing, {"topology.structure.data: particle id 2 has no row"});

    json unknown = valid_document();
    unknown["topology"]["structure"]["data"][2][0] = 7;
    expect_input_error(unknown, {"topology.structure.data[2][0]: particle id 7 is outside the state's ids 0..2"});

    json duplicated = valid_document();
    duplicated["topology"]["structure"]["data"][2][0] = 1;
    expect_input_error(duplicated,
                       {"topology.structure.data[2][0]: particle id 1 appears twice "
                        "(first at topology.structure.data[0])"});
}

// The four grouping columns of UAMMD-structured are integers and kept by particle id; resId and
// chainId (read by the PDB writer) stay empty when the structure has no such column.
TEST(Document, StructureGroupingColumns) {
    json document = valid_document();
    document["topology"]["structure"] = {{"labels", {"id", "type", "resId", "chainId", "modelId", "batchId"}},
                                         {"data", {{0, "A", 4, 1, 0, 2}, {1, "B", 5, 1, 1, 0}, {2, "B", 6, 2, 1, 1}}}};
    const ParsedDocument parsed = parse_document(document.dump());
    EXPECT_EQ(parsed.system.modelId, (std::vector<int32_t>{0, 1, 1}));
    EXPECT_EQ(parsed.system.batchId, (std::vector<int32_t>{2, 0, 1}));
    EXPECT_EQ(parsed.system.resId, (std::vector<int32_t>{4, 5, 6}));
    EXPECT_EQ(parsed.system.chainId, (std::vector<int32_t>{1, 1, 2}));
    consume_components(parsed);
    EXPECT_NO_THROW(parsed.root.check_all_used());

    const ParsedDocument plain = parse_document(valid_document().dump());
    EXPECT_TRUE(plain.system.resId.empty());
    EXPECT_TRUE(plain.system.chainId.empty());

    for (const char* label : {"resId", "chainId"}) {
        json bad = valid_document();
        bad["topology"]["structure"] = {{"labels", {"id", "type", label}},
                                        {"data", {{0, "A", 0}, {1, "B", "x"}, {2, "B", 0}}}};
        expect_input_error(bad, {"topology.structure.data[1][2]: expected a 32-bit integer"});
    }
}

TEST(Document, BoxLengthsMustBePositive) {
    json document = valid_document();
    document["global"]["ensemble"]["data"][0][0] = {10, -20, 30};
    expect_input_error(document, {"global.ensemble.data[0][0][1]: box length must be > 0"});
    document["global"]["ensemble"]["data"][0][0] = {10, 20};
    expect_input_error(document, {"global.ensemble.data[0][0]: expected [x, y, z]"});
    for (const json& bad : {json("wide"), json(nullptr), json(1e16), json("-inf"), json(true)}) {
        document["global"]["ensemble"]["data"][0][0] = {10, bad, 30};
        expect_input_error(document, {"global.ensemble.data[0][0][1]: box length must be > 0 and <= 1e15, or 0 or "
                                      "\"inf\" for an open (non-periodic) axis"});
    }
}

// UAMMD's Box takes a length of 0 or infinity as an open axis; JSON spells infinity "inf".
TEST(Document, BoxLengthsOfZeroOrInfAreOpenAxes) {
    json document = valid_document();
    document["global"]["ensemble"]["data"][0][0] = {0, "inf", 30};
    const ParsedDocument parsed = parse_document(document.dump());
    const SystemDescription& system = parsed.system;
    EXPECT_TRUE(std::isinf(system.box[0]) && system.box[0] > 0);
    EXPECT_TRUE(std::isinf(system.box[1]) && system.box[1] > 0);
    EXPECT_EQ(system.box[2], 30.0);
    EXPECT_EQ(system.boxPath, "global.ensemble.data[0][0]");
}

TEST(Document, EnsembleNeedsOneRowAndNonNegativeTemperature) {
    json twoRows = valid_document();
    twoRows["global"]["ensemble"]["data"].push_back({{1, 1, 1}, 1});
    expect_input_error(twoRows, {"global.ensemble.data: expected exactly one row, got 2"});

    json cold = valid_document();
    cold["global"]["ensemble"]["data"][0][1] = -1;
    expect_input_error(cold, {"global.ensemble.data[0][1]: temperature must be >= 0"});
}

TEST(Document, DuplicateTypeName) {
    json document = valid_document();
    document["global"]["types"]["data"][1][0] = "A";
    expect_input_error(document,
                       {"global.types.data[1][0]: type 'A' appears twice (first at global.types.data[0][0])"});
}

TEST(Document, GlobalEntriesByClass) {
    json twoUnits = valid_document();
    twoUnits["global"]["units"] = {{"type", {"Units", "None"}}};
    expect_input_error(twoUnits, {"a second Units entry in global"});

    json noTypes = valid_document();
    noTypes["global"].erase("types");
    expect_input_error(noTypes, {"global: missing the [Types, Basic] entry"});

    json unknownUnits = valid_document();
    unknownUnits["global"]["myUnits"]["type"][1] = "Furlongs";
    expect_input_error(unknownUnits, {"global.myUnits.type: unknown component [Units, Furlongs]"});

    json unknownClass = valid_document();
    unknownClass["global"]["extra"] = {{"type", {"Foo", "Bar"}}};
    expect_input_error(unknownClass, {"global.extra.type: unknown component [Foo, Bar]"});

    json typesMissingCharge = valid_document();
    typesMissingCharge["global"]["types"]["labels"] = {"name", "radius", "mass"};
    expect_input_error(typesMissingCharge, {"global.types.labels: missing required label 'charge'"});
}

TEST(Document, SystemEntries) {
    json backups = valid_document();
    backups["system"]["backup"] = {{"type", {"Simulation", "Backup"}},
                                   {"parameters", {{"backupFilePath", "b"}, {"backupIntervalStep", 10}}}};
    backups["system"]["again"] = backups["system"]["backup"];
    expect_input_error(backups, {"system.backup: a second [Simulation, Backup] entry", "system.again"});

    json noInterval = valid_document();
    noInterval["system"]["backup"] = {{"type", {"Simulation", "Backup"}}, {"parameters", {{"backupFilePath", "b"}}}};
    expect_input_error(noInterval, {"system.backup.parameters.backupIntervalStep: missing required entry"});

    // What UAMMD-structured writes into the documents it restarts from.
    json restarted = valid_document();
    restarted["system"]["backup"] = {{"type", {"Simulation", "Backup"}},
                                     {"parameters",
                                      {{"backupFilePath", "b"}, {"backupIntervalStep", 10},
                                       {"restartedFromBackup", true}, {"lastBackupStep", 500}}}};
    EXPECT_NO_THROW(parse_document(restarted.dump()).root.at("system").check_all_used());
    restarted["system"]["backup"]["parameters"]["lastBackupStep"] = -1;
    expect_input_error(restarted, {"system.backup.parameters.lastBackupStep", "expected a step >= 0"});
    restarted["system"]["backup"]["parameters"]["lastBackupStep"] = 5;
    restarted["system"]["backup"]["parameters"]["restartedFromBackup"] = "yes";
    expect_input_error(restarted, {"system.backup.parameters.restartedFromBackup"});

    json other = valid_document();
    other["system"]["other"] = {{"type", {"Simulation", "Restart"}}};
    expect_input_error(other, {"system.other.type: unknown component [Simulation, Restart]"});

    json nameless = valid_document();
    nameless["system"]["info"]["parameters"].erase("name");
    expect_input_error(nameless, {"system.info.parameters.name: missing required entry"});

    json negativeSeed = valid_document();
    negativeSeed["system"]["info"]["parameters"]["seed"] = -1;
    expect_input_error(negativeSeed, {"system.info.parameters.seed: expected a non-negative integer"});
}

TEST(Document, MalformedComponentType) {
    json document = valid_document();
    document["topology"]["forceField"]["lj"]["type"] = "NonBonded";
    expect_input_error(document, {"topology.forceField.lj.type: expected [Class, SubClass]"});
}

TEST(Document, UnknownTopLevelKeyWithSuggestion) {
    json document = valid_document();
    document["simulationStepp"] = document["simulationStep"];
    document.erase("simulationStep");
    const ParsedDocument parsed = parse_document(document.dump());
    consume_components(parsed);
    try {
        parsed.root.check_all_used();
        FAIL() << "no error was thrown";
    } catch (const Error& error) {
        EXPECT_EQ(error.status(), STRUCTMD_ERR_INPUT);
        EXPECT_NE(std::string(error.what()).find("simulationStepp: unknown entry (did you mean simulationStep?)"),
                  std::string::npos)
            << error.what();
    }
}

TEST(Document, UnknownParameterOfAComponentAfterItRead) {
    json document = valid_document();
    document["topology"]["forceField"]["lj"]["parameters"].erase("cutOffFactor");
    document["topology"]["forceField"]["lj"]["parameters"]["cutoffFactor"] = 2.5;
    const ParsedDocument parsed = parse_document(document.dump());
    for (const ComponentEntry& entry : parsed.system.forceField) {
        if (entry.name != "lj") {
            entry.node.mark_used();
            continue;
        }
        // What the Lennard-Jones reader would do: ask for the parameters it knows.
        const TrackedNode parameters = entry.node.at("parameters");
        EXPECT_EQ(parameters.get<std::string>("condition"), "all");
        EXPECT_FALSE(parameters.find("cutOffFactor").has_value());
    }
    for (const ComponentEntry& entry : parsed.system.integrators) entry.node.mark_used();
    for (const ComponentEntry& entry : parsed.system.simulationSteps) entry.node.mark_used();
    try {
        parsed.root.check_all_used();
        FAIL() << "no error was thrown";
    } catch (const Error& error) {
        EXPECT_EQ(error.status(), STRUCTMD_ERR_INPUT);
        EXPECT_NE(std::string(error.what())
                      .find("topology.forceField.lj.parameters.cutoffFactor: unknown parameter (did you mean "
                            "cutOffFactor?)"),
                  std::string::npos)
            << error.what();
    }
}

TEST(Document, UnknownKeyInASectionReadHere) {
    json document = valid_document();
    document["state"]["comment"] = "hello";
    expect_input_error(document, {"state.comment: unknown entry"});

    json parameters = valid_document();
    parameters["global"]["myUnits"]["parameters"] = {{"scale", 2}};
    expect_input_error(parameters, {"global.myUnits.parameters: unknown entry"});
}

TEST(Document, TableRowWithWrongCellCount) {
    json document = valid_document();
    document["state"]["data"][1] = {0, {0, 0, 0}};
    expect_input_error(document, {"state.data[1]: row has 2 cells, labels has 3"});
}

// UAMMD-structured's Magnetism-Dipolar generators write 5 cells under 4 state labels, which it reads
// by label: the cells past the labels are ignored, with one warning naming the first such row. Other
// tables still refuse them.
TEST(Document, StateRowsWithCellsPastTheLabelsAreReadByLabelWithAWarning) {
    json document = valid_document();
    document["state"] = {{"labels", {"id", "position", "velocity"}},
                         {"data", {{0, {0, 0, 0}, {1, 2, 3}}, {1, {1, 1, 1}, {0, 0, 0}, 4.5}, {2, {2, 2, 2}, {0, 1, 0}, 5.5}}}};
    const SystemDescription system = parse_document(document.dump()).system;
    ASSERT_EQ(system.velocities.size(), 3u);
    EXPECT_EQ(system.velocities[2], (Vec3d{0, 1, 0}));
    ASSERT_EQ(system.warnings.size(), 1u);
    EXPECT_NE(system.warnings[0].find("state.data[1]: row has 4 cells, labels has 3 (2 rows like it)"), std::string::npos)
        << system.warnings[0];
    EXPECT_TRUE(parse_document(valid_document().dump()).system.warnings.empty());

    json structure = valid_document();
    structure["topology"]["structure"]["data"][0].push_back(7);
    expect_input_error(structure, {"topology.structure.data[0]: row has 4 cells, labels has 3"});
}

// UAMMD-structured's ["Units","lenSI"]: SI with lengths in lengthScale metres (default 1).
TEST(Document, LenSIUnitsScaleBoltzmannAndCoulombByTheLengthScale) {
    json document = valid_document();
    document["global"]["myUnits"] = {{"type", {"Units", "lenSI"}}, {"parameters", {{"lengthScale", 1e-9}}}};
    const SystemDescription nano = parse_document(document.dump()).system;
    EXPECT_EQ(nano.units.name, "lenSI");
    EXPECT_NEAR(nano.units.boltzmann, 1.380649e-23 / 1e-27, 1e-12 * 1.380649e4);
    EXPECT_NEAR(nano.units.electricConversion, 8.987551e9 * 1e-18, 1e-12 * 8.987551e-9);
    document["global"]["myUnits"].erase("parameters");
    EXPECT_DOUBLE_EQ(parse_document(document.dump()).system.units.boltzmann, 1.380649e-23);
    document["global"]["myUnits"]["parameters"] = {{"lengthScale", -1.0}};
    expect_input_error(document, {"global.myUnits.parameters.lengthScale: lengthScale must be a positive length"});
}

// ["Types","Polarizable"]: each particle takes its type's polarizability, unless the state gives its
// own (which then wins, with a warning, as in UAMMD-structured).
TEST(Document, PolarizableTypesGiveEachParticleItsTypesPolarizability) {
    json document = valid_document();
    document["global"]["types"] = {{"type", {"Types", "Polarizable"}},
                                   {"labels", {"name", "radius", "mass", "charge", "polarizability"}},
                                   {"data", {{"A", 0.5, 1.0, 0.0, 1.5}, {"B", 1.0, 2.0, -1.0, 2.5}}}};
    const SystemDescription system = parse_document(document.dump()).system;
    // Particles 0, 1, 2 are of types A, B, B.
    EXPECT_EQ(system.stateColumns[StateColumn::polarizability], (std::vector<double>{1.5, 2.5, 2.5}));
    EXPECT_TRUE(system.warnings.empty());

    document["state"]["labels"].push_back("polarizability");
    for (json& row : document["state"]["data"]) row.push_back(9.0);
    const SystemDescription overridden = parse_document(document.dump()).system;
    EXPECT_EQ(overridden.stateColumns[StateColumn::polarizability], (std::vector<double>{9.0, 9.0, 9.0}));
    ASSERT_EQ(overridden.warnings.size(), 1u);
    EXPECT_NE(overridden.warnings[0].find("overrides the types'"), std::string::npos);

    json basic = valid_document();
    EXPECT_TRUE(parse_document(basic.dump()).system.stateColumns[StateColumn::polarizability].empty());
    basic["global"]["types"]["labels"].push_back("polarizability");
    expect_input_error(basic, {"global.types.labels[4]: unknown label 'polarizability'"});
}

TEST(Document, UnknownStateLabel) {
    json document = valid_document();
    document["state"]["labels"][2] = "colour";
    expect_input_error(document, {"state.labels[2]: unknown label 'colour'"});
}

TEST(Document, ScheduleIsRequiredWithIntegrators) {
    json document = valid_document();
    document["integrator"].erase("schedule");
    expect_input_error(document, {"integrator: missing the [Schedule, Integrator] entry"});
}

TEST(Document, ScheduleOrdersAreConsecutiveFromOne) {
    json gap = valid_document();
    gap["integrator"]["schedule"]["data"][0][0] = 3;
    expect_input_error(gap, {"integrator.schedule.data[0][0]: order 3 is outside 1..2"});

    json twice = valid_document();
    twice["integrator"]["schedule"]["data"][0][0] = 1;
    expect_input_error(twice, {"integrator.schedule.data[1][0]: order 1 appears twice "
                               "(first at integrator.schedule.data[0])"});
}

TEST(Document, ScheduleNamesExistingIntegratorsAndAllOfThem) {
    json unknown = valid_document();
    unknown["integrator"]["schedule"]["data"][0][1] = "nope";
    expect_input_error(unknown,
                       {"integrator.schedule.data[0][1]: unknown integrator 'nope' (integrators are bbk, vv)"});

    json unscheduled = valid_document();
    unscheduled["integrator"]["schedule"]["data"][0][1] = "bbk";
    expect_input_error(unscheduled, {"integrator.vv: integrator not in the schedule integrator.schedule"});
}

TEST(Document, ScheduleStepsAndCount) {
    json negative = valid_document();
    negative["integrator"]["schedule"]["data"][1][2] = -5;
    expect_input_error(negative, {"integrator.schedule.data[1][2]: steps must be >= 0"});

    json two = valid_document();
    two["integrator"]["another"] = two["integrator"]["schedule"];
    expect_input_error(two, {"a second schedule", "exactly one"});

    json wrongSubclass = valid_document();
    wrongSubclass["integrator"]["schedule"]["type"][1] = "Steps";
    expect_input_error(wrongSubclass, {"integrator.schedule.type: unknown component [Schedule, Steps]"});

    json missingLabel = valid_document();
    missingLabel["integrator"]["schedule"]["labels"] = {"order", "integrator"};
    expect_input_error(missingLabel, {"integrator.schedule.labels: missing required label 'steps'"});
}

}  // namespace
}  // namespace structmd::input
