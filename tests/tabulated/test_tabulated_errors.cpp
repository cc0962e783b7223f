// Bad tables through the C API: each is STRUCTMD_ERR_INPUT, and structmd_last_error names the JSON
// path of the culprit (and the file's line for a defect inside a table file).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tabulated_support.hpp"

namespace structmd_tabulated {
namespace {

std::string write_text(const std::string& name, const std::string& text) {
    const std::string path = std::string(STRUCTMD_TEST_TMP_DIR) + "/" + name;
    std::ofstream(path) << text;
    return path;
}

const std::string kGoodRows = "1 1.0 2.0 3.0\n2 1.5 1.0 2.0\n3 2.0 0.5 1.0\n";

// A pair entry reading `keyword` of a file with `text`.
Json pair_from_file(const std::string& text, const std::string& keyword = "T", double cutOff = 0.0) {
    const std::string file = write_text("bad.table", text);
    Json labels = {"name_i", "name_j", "file", "keyword"};
    Json row = {"A", "A", file, keyword};
    if (cutOff > 0) {
        labels.push_back("cutOff");
        row.push_back(cutOff);
    }
    return {{"type", {"NonBonded", "Tabulated"}}, {"parameters", {{"condition", "all"}, {"N", 100}}},
            {"labels", labels}, {"data", {row}}};
}

Json pair_inline(const Json& r, const Json& e, const Json& f) {
    return {{"type", {"NonBonded", "Tabulated"}}, {"parameters", {{"condition", "all"}, {"N", 100}}},
            {"labels", {"name_i", "name_j", "r", "energy", "force"}}, {"data", {{"A", "A", r, e, f}}}};
}

// Loads a two-particle scene with the entry as "t"; expects an input error whose message has every
// one of `parts`.
void expect_input_error(const Json& entry, const std::vector<std::string>& parts, bool pair = true) {
    Json ff = {{"t", entry}};
    if (pair) ff["nl"] = neighbour_list();
    int status = -1;
    SimHandle sim = load(document(8.0, {{0, 0, 0}, {1.2, 0, 0}, {0, 1.2, 0}}, {"A", "A", "A"}, ff), &status);
    EXPECT_EQ(status, STRUCTMD_ERR_INPUT);
    const std::string message = structmd_last_error(sim.get());
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
}

const std::string kRow = "topology.forceField.t.data[0]";

TEST(TabulatedErrors, MissingSection) {
    expect_input_error(pair_from_file("S\nN 3\n\n" + kGoodRows, "T"), {kRow + "[2]", "no section 'T'"});
}

TEST(TabulatedErrors, MissingFile) {
    Json entry = pair_from_file("");
    entry["data"][0][2] = "/nonexistent/structmd.table";
    expect_input_error(entry, {kRow + "[2]", "cannot open"});
}

// A device never ends (/dev/urandom) or never holds a table (/dev/zero); a directory cannot be read:
// each is refused before a byte is read (issue 37, defect 3).
TEST(TabulatedErrors, NotARegularFile) {
    Json entry = pair_from_file("");
    for (const char* device : {"/dev/urandom", "/dev/zero"}) {
        entry["data"][0][2] = device;
        expect_input_error(entry, {kRow + "[2]", device, "not a regular file"});
    }
    entry["data"][0][2] = STRUCTMD_TEST_TMP_DIR;
    expect_input_error(entry, {kRow + "[2]", "a directory, not a file"});
}

TEST(TabulatedErrors, MalformedLine) {
    expect_input_error(pair_from_file("T\nN 3\n\n1 1.0 2.0 3.0\n2 1.5 abc 2.0\n3 2.0 0.5 1.0\n"),
                       {kRow + "[2]", "bad.table:5", "not a number"});
    expect_input_error(pair_from_file("T\nN 3\n\n1 1.0 2.0 3.0\n2 1.5 1.0\n3 2.0 0.5 1.0\n"),
                       {kRow + "[2]", "bad.table:5", "expected 4 fields"});
}

TEST(TabulatedErrors, NDoesNotMatchTheRows) {
    expect_input_error(pair_from_file("T\nN 4\n\n" + kGoodRows), {kRow + "[2]", "only 3 rows"});
    expect_input_error(pair_from_file("T\nN 2\n\n" + kGoodRows), {kRow + "[2]", "more rows than its N = 2"});
    expect_input_error(pair_from_file("T\nFPRIME 0 0\n\n" + kGoodRows), {kRow + "[2]", "does not set N"});
}

TEST(TabulatedErrors, ACutoffTooLongForTheBoxNamesTheRowThatSetsIt) {
    // The box is 8: a table reaching r = 5 is longer than half of it.
    const std::string rows = "1 1.0 2.0 3.0\n2 3.0 1.0 2.0\n3 5.0 0.5 1.0\n";
    expect_input_error(pair_from_file("T\nN 3\n\n" + rows), {kRow, "not shorter than half the box"});
    expect_input_error(pair_from_file("T\nN 3\n\n" + rows, "T", 4.5), {kRow + "[4]", "not shorter than half the box"});
}

// strtod reads "nan" and "inf"; a table's numbers must be finite, in its rows and its keywords
// (FPRIME nan 0 loaded and gave NaN energies; issue 37, defect 9).
TEST(TabulatedErrors, NonFiniteNumbers) {
    expect_input_error(pair_from_file("T\nN 3 FPRIME nan 0\n\n" + kGoodRows), {kRow + "[2]", "FPRIME", "'nan'"});
    expect_input_error(pair_from_file("T\nN 3 FPRIME 0 inf\n\n" + kGoodRows), {kRow + "[2]", "FPRIME", "'inf'"});
    expect_input_error(pair_from_file("T\nN 3\n\n1 1.0 2.0 3.0\n2 1.5 nan 2.0\n3 2.0 0.5 1.0\n"),
                       {kRow + "[2]", "bad.table:5", "not a number: 'nan'"});
}

TEST(TabulatedErrors, UnknownOrUnsupportedKeyword) {
    expect_input_error(pair_from_file("T\nN 3 FOO 1\n\n" + kGoodRows), {kRow + "[2]", "unknown keyword 'FOO'"});
    expect_input_error(pair_from_file("T\nN 3 BITMAP 1 2\n\n" + kGoodRows), {kRow + "[2]", "BITMAP"});
    expect_input_error(pair_from_file("T\nN 3 FP 0 0\n\n" + kGoodRows), {"unknown keyword 'FP'"});  // a bond keyword
}

TEST(TabulatedErrors, NonMonotonicDistances) {
    expect_input_error(pair_from_file("T\nN 3\n\n1 1.0 2.0 3.0\n2 0.9 1.0 2.0\n3 2.0 0.5 1.0\n"),
                       {kRow + "[2]", "increase strictly"});
    expect_input_error(pair_inline({1.0, 1.5, 1.5}, {1, 2, 3}, {1, 2, 3}), {kRow + "[2]", "increase strictly"});
}

TEST(TabulatedErrors, ColumnsOfDifferentLengths) {
    expect_input_error(pair_inline({1.0, 1.5, 2.0}, {1, 2}, {1, 2, 3}), {kRow + "[3]", "has 2 values"});
}

TEST(TabulatedErrors, CutoffOutsideTheTable) {
    expect_input_error(pair_from_file("T\nN 3\n\n" + kGoodRows, "T", 2.5), {kRow + "[4]", "must lie in"});
}

TEST(TabulatedErrors, MissingOrMixedLabelsAndParameters) {
    Json entry = pair_inline({1.0, 1.5, 2.0}, {1, 2, 3}, {1, 2, 3});
    entry["parameters"].erase("N");
    expect_input_error(entry, {"topology.forceField.t.parameters.N"});
    Json mixed = pair_inline({1.0, 1.5, 2.0}, {1, 2, 3}, {1, 2, 3});
    mixed["labels"] = {"name_i", "name_j", "r", "energy", "file"};
    expect_input_error(mixed, {"topology.forceField.t.labels"});
}

TEST(TabulatedErrors, BondTables) {
    const Json ids = {{"labels", {"id_i", "id_j"}}, {"data", {{0, 1}}}};
    Json both = {{"type", {"Bond2", "Tabulated"}},
                 {"parameters", {{"N", 10}, {"file", "x"}, {"keyword", "B"}, {"r", {1, 2}}, {"energy", {1, 2}}, {"force", {1, 2}}}}};
    both.update(ids);
    expect_input_error(both, {"topology.forceField.t.parameters", "either from a file"}, false);
    const std::string file = write_text("bad_bond.table", "B\nN 3 FP 0 0 EQ 1.0 RSQ 1 2\n\n" + kGoodRows);
    Json rsq = {{"type", {"Bond2", "Tabulated"}}, {"parameters", {{"N", 10}, {"file", file}, {"keyword", "B"}}}};
    rsq.update(ids);
    expect_input_error(rsq, {"topology.forceField.t.parameters.file", "unknown keyword 'RSQ'"}, false);
    const std::string angles = write_text("bad_angle.table", "A\nN 3\n\n1 0.0 1.0 1.0\n2 90.0 0.0 0.0\n3 170.0 1.0 1.0\n");
    Json angle = {{"type", {"Bond3", "Tabulated"}}, {"parameters", {{"N", 10}, {"file", angles}, {"keyword", "A"}}},
                  {"labels", {"id_i", "id_j", "id_k"}}, {"data", {{0, 1, 2}}}};
    expect_input_error(angle, {"topology.forceField.t.parameters.file", "0 to 180 degrees"}, false);
}

TEST(TabulatedErrors, DihedralTables) {
    const auto entry = [](const std::string& text) {
        const std::string file = write_text("bad_dihedral.table", text);
        return Json{{"type", {"Bond4", "Tabulated"}}, {"parameters", {{"N", 36}, {"file", file}, {"keyword", "D"}}},
                    {"labels", {"id_i", "id_j", "id_k", "id_l"}}, {"data", {{0, 1, 2, 3}}}};
    };
    expect_input_error(entry("D\nN 3\n\n1 0.0 1.0 0.0\n2 180.0 0.0 0.0\n3 360.0 1.0 0.0\n"),
                       {"topology.forceField.t.parameters.file", "less than 360 degrees"}, false);
    expect_input_error(entry("D\nN 3 NOF\n\n1 0.0 1.0 0.0\n2 90.0 0.0 0.0\n3 180.0 1.0 0.0\n"),
                       {"bad_dihedral.table:4", "expected 3 fields"}, false);
    expect_input_error(entry("D\nN 3 CHECKU u.txt\n\n1 0.0 1.0 0.0\n2 90.0 0.0 0.0\n3 180.0 1.0 0.0\n"),
                       {"topology.forceField.t.parameters.file", "CHECKU"}, false);
    expect_input_error(entry("D\nN 3 FP 0 0\n\n1 0.0 1.0 0.0\n2 90.0 0.0 0.0\n3 180.0 1.0 0.0\n"),
                       {"unknown keyword 'FP'"}, false);
}

}  // namespace
}  // namespace structmd_tabulated
