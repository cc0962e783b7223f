// TrackedNode and Table on small documents built in place: typed reads, used-key tracking and the
// messages that name the path of the culprit.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "input/tracked_node.hpp"

namespace structmd::input {
namespace {

using nlohmann::json;

// A document and its root node; the state owns the document so that nodes stay valid.
TrackedNode root_of(json document) {
    auto state = std::make_shared<TrackingState>();
    state->document = std::move(document);
    return TrackedNode(state, &state->document, "");
}

// Runs action, which must throw an input error whose message contains every fragment.
template <class Action>
void expect_input_error(Action action, std::initializer_list<std::string> fragments) {
    try {
        action();
        FAIL() << "no error was thrown";
    } catch (const Error& error) {
        EXPECT_EQ(error.status(), STRUCTMD_ERR_INPUT) << error.what();
        for (const std::string& fragment : fragments)
            EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos)
                << "message: " << error.what() << "\nexpected to contain: " << fragment;
    }
}

TEST(TrackedNode, TypedReadsReturnTheValues) {
    const TrackedNode root = root_of(json::parse(R"({"x": 1.5, "n": -3, "big": 7, "whole": 4.0, "flag": true,
        "name": "lj", "v": [1, 2, 3.5], "ids": [0, 5, -2]})"));
    EXPECT_DOUBLE_EQ(root.get<double>("x"), 1.5);
    EXPECT_EQ(root.get<int64_t>("n"), -3);
    EXPECT_EQ(root.get<int32_t>("n"), -3);
    EXPECT_EQ(root.get<uint64_t>("big"), 7u);
    EXPECT_EQ(root.get<int64_t>("whole"), 4);
    EXPECT_TRUE(root.get<bool>("flag"));
    EXPECT_EQ(root.get<std::string>("name"), "lj");
    EXPECT_EQ((root.get<std::array<double, 3>>("v")), (std::array<double, 3>{1, 2, 3.5}));
    EXPECT_EQ(root.get<std::vector<double>>("v"), (std::vector<double>{1, 2, 3.5}));
    EXPECT_EQ(root.get<std::vector<int64_t>>("ids"), (std::vector<int64_t>{0, 5, -2}));
    EXPECT_DOUBLE_EQ(root.get_or<double>("absent", 2.5), 2.5);
}

TEST(TrackedNode, TypeMismatchNamesThePathAndTheValue) {
    const TrackedNode root = root_of(json::parse(R"({"p": {"K": "ten", "n": 2.5, "s": -1, "v": [1, "y", 3]}})"));
    const TrackedNode parameters = root.at("p");
    expect_input_error([&] { parameters.get<double>("K"); }, {"p.K: expected a number", "\"ten\""});
    expect_input_error([&] { parameters.get<int64_t>("n"); }, {"p.n: expected an integer", "2.5"});
    expect_input_error([&] { parameters.get<uint64_t>("s"); }, {"p.s: expected a non-negative integer"});
    expect_input_error([&] { parameters.get<std::array<double, 3>>("v"); }, {"p.v[1]: expected a number"});
    expect_input_error([&] { parameters.get<double>("absent"); }, {"p.absent: missing required entry"});
    expect_input_error([&] { parameters.at("K").at(0); }, {"p.K: expected an array"});
}

TEST(TrackedNode, Int32RejectsValuesOutOfRange) {
    const TrackedNode root = root_of(json::parse(R"({"n": 3000000000})"));
    expect_input_error([&] { root.get<int32_t>("n"); }, {"n: expected a 32-bit integer"});
}

TEST(TrackedNode, KeysKeepTheOrderTheStateRecords) {
    auto state = std::make_shared<TrackingState>();
    state->document = json::parse(R"({"b": 1, "a": 2})");
    state->keyOrder[""] = {"b", "a"};
    const TrackedNode root(state, &state->document, "");
    EXPECT_EQ(root.keys(), (std::vector<std::string>{"b", "a"}));
}

TEST(TrackedNode, CheckAllUsedSuggestsTheAskedKey) {
    const TrackedNode root =
        root_of(json::parse(R"({"topology": {"forceField": {"lj": {"parameters": {"cutoffFactor": 2.5}}}}})"));
    const TrackedNode parameters = root.at("topology").at("forceField").at("lj").at("parameters");
    EXPECT_FALSE(parameters.find("cutOffFactor").has_value());
    expect_input_error([&] { root.check_all_used(); },
                       {"topology.forceField.lj.parameters.cutoffFactor: unknown parameter",
                        "did you mean cutOffFactor?"});
}

TEST(TrackedNode, CheckAllUsedListsKnownKeysWhenNoneIsClose) {
    const TrackedNode root = root_of(json::parse(R"({"entry": {"alpha": 1, "zzzzzz": 2}})"));
    EXPECT_EQ(root.at("entry").get<int64_t>("alpha"), 1);
    EXPECT_FALSE(root.at("entry").has("beta"));
    expect_input_error([&] { root.check_all_used(); }, {"entry.zzzzzz: unknown entry", "known here: alpha, beta"});
}

TEST(TrackedNode, CheckAllUsedPassesWhenEverythingWasRead) {
    const TrackedNode root = root_of(json::parse(R"({"a": {"b": [1, {"c": 2}]}, "d": {"e": {"f": 1}}})"));
    EXPECT_EQ(root.at("a").at("b").at(1).get<int64_t>("c"), 2);
    root.at("d").mark_used();
    EXPECT_NO_THROW(root.check_all_used());
}

TEST(TrackedNode, CheckAllUsedLooksIntoObjectsInsideArrays) {
    const TrackedNode root = root_of(json::parse(R"({"a": [{"c": 1, "typo": 2}]})"));
    EXPECT_EQ(root.at("a").at(0).get<int64_t>("c"), 1);
    expect_input_error([&] { root.check_all_used(); }, {"a[0].typo: unknown entry"});
}

TEST(TrackedNode, UnreadSectionIsUnknown) {
    const TrackedNode root = root_of(json::parse(R"({"state": {}, "simulationStepp": {}})"));
    root.at("state").mark_used();
    EXPECT_FALSE(root.has("simulationStep"));
    expect_input_error([&] { root.check_all_used(); },
                       {"simulationStepp: unknown entry", "did you mean simulationStep?"});
}

TEST(Table, ReadsCellsByLabel) {
    const TrackedNode root = root_of(json::parse(R"({"t": {"labels": ["id", "position", "mass"],
        "data": [[0, [1, 2, 3], 2.0], [1, [4, 5, 6], 3.0]]}})"));
    const Table table = read_table(root.at("t"), {"id", "position"}, {"mass", "charge"});
    ASSERT_EQ(table.rows(), 2u);
    EXPECT_TRUE(table.has("mass"));
    EXPECT_FALSE(table.has("charge"));
    EXPECT_EQ((table.cell(1, "position").as<std::array<double, 3>>()), (std::array<double, 3>{4, 5, 6}));
    EXPECT_EQ(table.cell(1, "mass").path(), "t.data[1][2]");
    EXPECT_EQ(table.row(0).path(), "t.data[0]");
    EXPECT_NO_THROW(root.check_all_used());
}

TEST(Table, UnknownLabelIsNamed) {
    const TrackedNode root = root_of(json::parse(R"({"t": {"labels": ["id", "postion"], "data": []}})"));
    expect_input_error([&] { read_table(root.at("t"), {"id"}, {"position"}); },
                       {"t.labels[1]: unknown label 'postion'", "did you mean position?"});
}

TEST(Table, UnknownLabelFarFromAnyListsTheKnownOnes) {
    const TrackedNode root = root_of(json::parse(R"({"t": {"labels": ["id", "colour"], "data": []}})"));
    expect_input_error([&] { read_table(root.at("t"), {"id"}, {"mass"}); },
                       {"t.labels[1]: unknown label 'colour'", "expected one of id, mass"});
}

TEST(Table, RepeatedAndMissingLabels) {
    const TrackedNode repeated = root_of(json::parse(R"({"t": {"labels": ["id", "id"], "data": []}})"));
    expect_input_error([&] { read_table(repeated.at("t"), {"id"}); },
                       {"t.labels[1]: label 'id' repeats (first at t.labels[0])"});
    const TrackedNode missing = root_of(json::parse(R"({"t": {"labels": ["id"], "data": []}})"));
    expect_input_error([&] { read_table(missing.at("t"), {"id", "position"}); },
                       {"t.labels: missing required label 'position'"});
}

TEST(Table, RowWithWrongCellCount) {
    const TrackedNode root = root_of(json::parse(R"({"t": {"labels": ["id", "mass"], "data": [[0, 1], [1, 2, 3]]}})"));
    expect_input_error([&] { read_table(root.at("t"), {"id", "mass"}); }, {"t.data[1]: row has 3 cells, labels has 2"});
}

TEST(Table, MissingDataIsNamed) {
    const TrackedNode root = root_of(json::parse(R"({"t": {"labels": ["id"]}})"));
    expect_input_error([&] { read_table(root.at("t"), {"id"}); }, {"t.data: missing required entry"});
}

}  // namespace
}  // namespace structmd::input
