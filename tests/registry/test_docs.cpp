// registry.docs: docs/input-format.md documents every parameter of every registry entry. Each entry
// of the force-field and integrator registries, and each neighbour-list condition, has its
// `### ["Class","SubClass"]` section (an integrator registered under a second name may instead be
// named in the section of the one it repeats), and that section's table has a row for each
// parameter of the entry's schema, which says, where the table has the columns, whether the
// parameter goes in "parameters" or in the "labels" of the table, and whether it is required.
// The simulation steps' registry is walked alike. (That every documented section is a registry entry
// is tests/python/test_docs_components.py's part.)
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "forcefield/read_forcefield.hpp"
#include "integrators/integrator_spec.hpp"
#include "registry_inputs.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd::registry_test {
namespace {

// One row of a markdown table, its cells by the header of their column.
struct TableRow {
    std::vector<std::string> cells;
    std::map<std::string, std::string> byHeader;
};

struct Section {
    int line = 0;  // of its heading, 1-based
    std::vector<std::string> lines;
};

std::string trim(const std::string& s) {
    const size_t first = s.find_first_not_of(" \t");
    if (first == std::string::npos) return "";
    return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// The cells of "| a | b \| c |": an escaped bar belongs to its cell.
std::vector<std::string> cells_of(const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    for (size_t k = 1; k < line.size(); ++k) {
        if (line[k] == '|' && line[k - 1] != '\\') {
            cells.push_back(trim(cell));
            cell.clear();
        } else {
            cell += line[k];
        }
    }
    return cells;
}

// The `### ["Class","SubClass"]` sections of the page, by heading ("["Class","SubClass"]"), each up to
// the next heading of level 2 or 3.
std::map<std::string, Section> read_sections(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(STRUCTMD_ERR_IO, "cannot read " + path);
    std::map<std::string, Section> sections;
    const std::regex heading(R"re(^### (\["[^"]+","[^"]+"\])\s*$)re");
    Section* current = nullptr;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::smatch match;
        if (std::regex_match(line, match, heading)) {
            current = &sections[match[1].str()];
            current->line = number;
            continue;
        }
        if (line.rfind("## ", 0) == 0 || line.rfind("### ", 0) == 0) current = nullptr;
        if (current) current->lines.push_back(line);
    }
    return sections;
}

// Every table row of a section but header and separator rows.
std::vector<TableRow> table_rows(const Section& section) {
    std::vector<TableRow> rows;
    std::vector<std::string> header;
    bool inTable = false;
    for (const std::string& line : section.lines) {
        if (line.rfind("|", 0) != 0) {
            inTable = false;
            continue;
        }
        const std::vector<std::string> cells = cells_of(line);
        if (!inTable) {
            header = cells;
            inTable = true;
            continue;
        }
        if (!cells.empty() && cells[0].rfind("---", 0) == 0) continue;
        TableRow row;
        row.cells = cells;
        for (size_t k = 0; k < cells.size() && k < header.size(); ++k) row.byHeader[header[k]] = cells[k];
        rows.push_back(row);
    }
    return rows;
}

// The row whose first cell names `name` in backticks (a row may name several: `id_i`, `id_j`).
const TableRow* row_naming(const std::vector<TableRow>& rows, const std::string& name) {
    for (const TableRow& row : rows)
        if (!row.cells.empty() && row.cells[0].find("`" + name + "`") != std::string::npos) return &row;
    return nullptr;
}

std::string heading_of(const ComponentKey& key) { return "[\"" + key.cls + "\",\"" + key.subclass + "\"]"; }

const std::map<std::string, Section>& sections() {
    static const std::map<std::string, Section> all = read_sections(STRUCTMD_INPUT_FORMAT_DOC);
    return all;
}

// How a parameter is given: where, and whether it must be.
struct Documented {
    std::string name;
    const char* in;  // "parameters" or "labels"
    bool required;
};

// The section's rows for each parameter agree with the registry.
void expect_documented(const Section& section, const std::vector<Documented>& parameters) {
    const std::vector<TableRow> rows = table_rows(section);
    for (const Documented& p : parameters) {
        SCOPED_TRACE("parameter " + p.name);
        const TableRow* row = row_naming(rows, p.name);
        if (!row) {
            ADD_FAILURE() << "the section has no table row for `" << p.name << "`";
            continue;
        }
        const auto in = row->byHeader.find("in");
        if (in != row->byHeader.end()) EXPECT_EQ(in->second, p.in) << "where the parameter is given";
        const auto fallback = row->byHeader.find("default");
        if (fallback != row->byHeader.end() && std::string(p.in) == "parameters")
            EXPECT_EQ(fallback->second == "required", p.required) << "the default column says '" << fallback->second << "'";
    }
}

std::vector<Documented> documented_parameters(const ForceFieldComponent& c) {
    std::vector<Documented> all;
    for (const Parameter& p : c.parameters) {
        const bool once = c.kind == InteractionKind::external || is_common(c, p);
        all.push_back({p.name, once ? "parameters" : "labels", p.required()});
    }
    for (const Parameter& p : c.entryParameters) all.push_back({p.name, "parameters", p.required()});
    for (const Parameter& p : c.typeParameters) all.push_back({p.name, "labels", p.required()});
    if (!c.typeParameters.empty()) all.push_back({"name", "labels", true});
    return all;
}

TEST(RegistryDocs, ThePageHasComponentSections) {
    EXPECT_GT(sections().size(), 40u) << "read from " << STRUCTMD_INPUT_FORMAT_DOC;
}

TEST(RegistryDocs, EveryForceFieldEntryIsDocumentedWithEachOfItsParameters) {
    for (const ForceFieldComponent& c : forcefield_registry().entries()) {
        SCOPED_TRACE(c.key.text());
        const auto section = sections().find(heading_of(c.key));
        if (section == sections().end()) {
            ADD_FAILURE() << "docs/input-format.md has no section ### " << heading_of(c.key);
            continue;
        }
        SCOPED_TRACE("docs/input-format.md:" + std::to_string(section->second.line));
        expect_documented(section->second, documented_parameters(c));
    }
}

// An integrator either has its own section, or is a second name of one that has, named in that
// section (["Minimization","SteepestDescent"] in the section of ["SteepestDescent","SteepestDescent"]),
// whose schema it shares.
TEST(RegistryDocs, EveryIntegratorIsDocumentedWithEachOfItsParameters) {
    for (const IntegratorComponent& c : integrator_registry().entries()) {
        SCOPED_TRACE(c.key.text());
        const Section* section = nullptr;
        const auto own = sections().find(heading_of(c.key));
        if (own != sections().end()) {
            section = &own->second;
        } else {
            for (const IntegratorComponent& other : integrator_registry().entries()) {
                const auto found = sections().find(heading_of(other.key));
                if (found == sections().end()) continue;
                bool named = false;
                for (const std::string& line : found->second.lines)
                    named = named || line.find("`" + heading_of(c.key) + "`") != std::string::npos;
                if (!named) continue;
                std::vector<std::string> mine, theirs;
                for (const Parameter& p : c.parameters) mine.push_back(p.name);
                for (const Parameter& p : other.parameters) theirs.push_back(p.name);
                EXPECT_EQ(mine, theirs) << "named in the section of " << other.key.text() << " with other parameters";
                section = &found->second;
            }
        }
        if (!section) {
            ADD_FAILURE() << "docs/input-format.md has no section ### " << heading_of(c.key)
                          << ", nor names it in the section of another integrator";
            continue;
        }
        SCOPED_TRACE("docs/input-format.md:" + std::to_string(section->line));
        std::vector<Documented> parameters;
        for (const Parameter& p : c.parameters) parameters.push_back({p.name, "parameters", p.required()});
        expect_documented(*section, parameters);
    }
}

TEST(RegistryDocs, EverySimulationStepIsDocumentedWithEachOfItsParameters) {
    EXPECT_FALSE(simulation_step_registry().entries().empty());
    for (const SimulationStepEntry& step : simulation_step_registry().entries()) {
        SCOPED_TRACE(step.key.text());
        const auto section = sections().find(heading_of(step.key));
        if (section == sections().end()) {
            ADD_FAILURE() << "docs/input-format.md has no section ### " << heading_of(step.key);
            continue;
        }
        SCOPED_TRACE("docs/input-format.md:" + std::to_string(section->second.line));
        std::vector<Documented> parameters;
        for (const StepParameter& p : step.parameters) parameters.push_back({p.name, "parameters", p.required()});
        expect_documented(section->second, parameters);
    }
}

// The neighbour-list conditions, whose parameters the reader declares inline, named here; each has its
// section, ["NBody", "all"] too.
TEST(RegistryDocs, EveryNeighbourListConditionIsDocumentedWithItsParameters) {
    const std::vector<ComponentKey> keys = neighbour_list_keys();
    EXPECT_GE(keys.size(), 3u);
    for (const ComponentKey& key : keys) {
        SCOPED_TRACE(key.text());
        const auto section = sections().find(heading_of(key));
        if (section == sections().end()) {
            ADD_FAILURE() << "docs/input-format.md has no section ### " << heading_of(key);
            continue;
        }
        SCOPED_TRACE("docs/input-format.md:" + std::to_string(section->second.line));
        // ["NBody", "all"] builds no list: it takes no parameters.
        if (key.cls == "NBody") continue;
        expect_documented(section->second, {{"cutOffVerletFactor", "parameters", false}, {"cutOff", "parameters", false}});
    }
}

}  // namespace
}  // namespace structmd::registry_test
