// The reader's side of the tabulated components (tabulated.hpp): each entry's tables, inline or from
// LAMMPS table files, checked and resampled as LAMMPS's `table spline N` styles do; every defect is an
// input error naming the JSON path that gave it.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/lammps_table_file.hpp"
#include "forcefield/tabulated.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;
using input::TrackedNode;

namespace {

constexpr double kDegree = M_PI / 180.0;  // LAMMPS's angle tables are in degrees

Parameter table_length_parameter() { return number("N", "1", Must::be_integer); }

// N, the number of nodes the table is resampled onto (LAMMPS's `table spline N`).
int table_length(const ComponentEntry& entry) {
    const double n = input::read_parameters(entry.node, {table_length_parameter()})["N"];
    if (n < 2 || n > 1e7) throw input_error(entry.node.path() + ".parameters.N", "N must be between 2 and 10^7");
    return static_cast<int>(n);
}

// Abscissae strictly increasing and every value finite; `xs` names the abscissae for messages.
void check_points(const TablePoints& t, const std::string& path) {
    if (t.x.size() < 2) throw input_error(path, "a table needs at least 2 points");
    for (size_t i = 0; i < t.x.size(); ++i) {
        if (!std::isfinite(t.x[i]) || !std::isfinite(t.energy[i]) || (!t.force.empty() && !std::isfinite(t.force[i])))
            throw input_error(path, "point " + std::to_string(i + 1) + " is not finite");
        if (i > 0 && !(t.x[i] > t.x[i - 1]))
            throw input_error(path, "the abscissae must increase strictly (point " + std::to_string(i + 1) + ": " +
                                        std::to_string(t.x[i]) + " after " + std::to_string(t.x[i - 1]) + ")");
    }
}

// An inline table: lists of numbers of one length (no force list: a dihedral table without forces).
TablePoints inline_points(const TrackedNode& x, const TrackedNode& energy, const TrackedNode* force) {
    TablePoints t;
    t.x = x.as<std::vector<double>>();
    t.energy = energy.as<std::vector<double>>();
    if (force) t.force = force->as<std::vector<double>>();
    for (const auto* column : {&energy, force}) {
        if (!column) continue;
        const size_t size = column->as<std::vector<double>>().size();
        if (size != t.x.size())
            throw input_error(column->path(), "has " + std::to_string(size) + " values, the abscissae " +
                                                  std::to_string(t.x.size()));
    }
    check_points(t, x.path());
    return t;
}

TablePoints file_points(const LammpsTableSection& s) {
    TablePoints t;
    t.x = s.x;
    t.energy = s.energy;
    t.force = s.force;
    return t;
}

// The force slopes of an FP / FPRIME keyword, times `scale`.
void read_force_slopes(const LammpsTableSection& s, const char* keyword, double scale, const std::string& path,
                       TablePoints& t) {
    if (!s.has(keyword)) return;
    t.hasForceSlopes = true;
    t.forceSlopeLow = s.number(keyword, 0, path) * scale;
    t.forceSlopeHigh = s.number(keyword, 1, path) * scale;
}

// ---- NonBonded ----------------------------------------------------------------------------------

int type_index(const SystemDescription& system, const TrackedNode& cell) {
    const int id = system.typeId(cell.as<std::string>());
    if (id < 0) throw input_error(cell.path(), "unknown type '" + cell.as<std::string>() + "'");
    return id;
}

// A pair table file section: N, R / RSQ rlo rhi (abscissae recomputed from them, as LAMMPS does),
// FPRIME; BITMAP is refused.
TablePoints pair_file_points(const TrackedNode& file, const TrackedNode& keyword) {
    const std::string path = file.path();
    const LammpsTableSection s = read_lammps_table(file.as<std::string>(), keyword.as<std::string>(),
                                                   {{"R", 2}, {"RSQ", 2}, {"BITMAP", 2}, {"FPRIME", 2}}, path);
    if (s.has("BITMAP")) throw input_error(path, "BITMAP tables are not supported (only R, RSQ, FPRIME and N)");
    TablePoints t = file_points(s);
    read_force_slopes(s, "FPRIME", 1.0, path, t);
    if (s.has("R") && s.has("RSQ")) throw input_error(path, "a table gives R or RSQ, not both");
    for (const char* spacing : {"R", "RSQ"}) {
        if (!s.has(spacing)) continue;
        t.hasRange = true;
        t.inner = s.number(spacing, 0, path);
        t.outer = s.number(spacing, 1, path);
        const double last = s.n - 1;
        for (int i = 0; i < s.n; ++i)
            t.x[i] = std::string(spacing) == "R"
                         ? t.inner + (t.outer - t.inner) * i / last
                         : std::sqrt(t.inner * t.inner + (t.outer * t.outer - t.inner * t.inner) * i / last);
    }
    check_points(t, path);
    return t;
}

ForceFieldComponent configure_pair(ForceFieldComponent c, const ComponentEntry& entry, const SystemDescription& system) {
    const int n = table_length(entry);
    const input::Table table =
        input::read_table(entry.node, {"name_i", "name_j"}, {"file", "keyword", "r", "energy", "force", "cutOff"});
    const std::string labels = entry.node.path() + ".labels";
    const bool fromFile = table.has("file") || table.has("keyword");
    const bool given = table.has("r") || table.has("energy") || table.has("force");
    if (fromFile == given)
        throw input_error(labels, "give each type pair's table either from a file (labels file, keyword) or inline "
                                  "(labels r, energy, force)");
    for (const char* label : fromFile ? std::vector<const char*>{"file", "keyword"}
                                      : std::vector<const char*>{"r", "energy", "force"})
        if (!table.has(label)) throw input_error(labels, std::string("missing label '") + label + "'");

    auto config = std::make_shared<PairTableConfig>();
    std::set<std::pair<int, int>> seen;
    double largest = 0.0;
    for (size_t r = 0; r < table.rows(); ++r) {
        PairTableConfig::Row row;
        row.typeI = type_index(system, table.cell(r, "name_i"));
        row.typeJ = type_index(system, table.cell(r, "name_j"));
        if (!seen.insert(std::minmax(row.typeI, row.typeJ)).second)
            throw input_error(table.row(r).path(), "type pair listed twice");
        TablePoints t;
        if (fromFile) {
            t = pair_file_points(table.cell(r, "file"), table.cell(r, "keyword"));
        } else {
            const TrackedNode force = table.cell(r, "force");
            t = inline_points(table.cell(r, "r"), table.cell(r, "energy"), &force);
        }
        const double inner = t.hasRange ? t.inner : t.x.front();
        const double outer = t.hasRange ? t.outer : t.x.back();
        row.cutoff = table.has("cutOff") ? table.cell(r, "cutOff").as<double>() : outer;
        const std::string where = table.has("cutOff") ? table.cell(r, "cutOff").path() : table.row(r).path();
        if (!(inner > 0.0)) throw input_error(where, "the table's inner radius must be positive");
        if (!(row.cutoff > inner && row.cutoff <= outer))
            throw input_error(where, "the cutoff " + std::to_string(row.cutoff) + " must lie in the table's (" +
                                         std::to_string(inner) + ", " + std::to_string(outer) + "]");
        row.nodes = lammps_pair_spline(t, n, row.cutoff);
        if (row.cutoff > largest) {
            largest = row.cutoff;
            c.cutoffPath = where;
        }
        config->rows.push_back(std::move(row));
    }
    c.config = config;
    c.actingCutoff = [largest](const ParameterValues&, const Constants&, double, bool) { return largest; };
    return c;
}

// ---- bonds --------------------------------------------------------------------------------------

// What differs between the bond tables: the file's keywords and row width, the unit of a file's
// abscissa (angles: degrees; dihedrals: degrees unless RADIANS), the inline abscissa's name, whether
// the force may be left out, the checks of the points' range and the resampling.
struct BondTableKind {
    const char* abscissa;  // the inline label: "r", "theta" or "phi"
    std::map<std::string, int> keywords;
    int (*columns)(const LammpsTableSection&);            // null: 4
    double (*file_unit)(const LammpsTableSection&);       // file abscissa -> radians or length
    bool forceOptional;
    void (*prepare)(TablePoints&, const std::string& path);  // range checks, re-imaging
    TableNodes (*resample)(const TablePoints&, int);
};

double unit_length(const LammpsTableSection&) { return 1.0; }
double unit_degree(const LammpsTableSection&) { return kDegree; }
double dihedral_unit(const LammpsTableSection& s) { return s.has("RADIANS") ? 1.0 : kDegree; }
int dihedral_columns(const LammpsTableSection& s) { return s.has("NOF") ? 3 : 4; }

void any_range(TablePoints&, const std::string&) {}

// LAMMPS's angle tables span 0..180 degrees; its resampled table spans [0, pi] whatever the points.
void angle_range(TablePoints& t, const std::string& path) {
    constexpr double tiny = 1e-8 * kDegree;
    if (std::fabs(t.x.front()) > tiny || std::fabs(t.x.back() - M_PI) > tiny)
        throw input_error(path, "an angle table must range from 0 to 180 degrees (0 to pi radians)");
}

// A dihedral table spans less than a turn and is periodic: its points are taken into [0, 2 pi) and
// rotated to increase again, as LAMMPS does.
void dihedral_range(TablePoints& t, const std::string& path) {
    constexpr double turn = 2.0 * M_PI;
    if (t.x.size() < 3) throw input_error(path, "a dihedral table needs at least 3 points");
    if (!(t.x.back() - t.x.front() < turn))
        throw input_error(path, "a dihedral table must span less than 360 degrees (2 pi radians)");
    size_t start = 0;
    std::vector<double> x(t.x.size());
    for (size_t i = 0; i < t.x.size(); ++i) {
        x[i] = t.x[i] - turn * std::floor(t.x[i] / turn);
        if (i > 0 && x[i] < x[i - 1]) start = i;
    }
    const auto rotate = [&](std::vector<double>& v) { std::rotate(v.begin(), v.begin() + start, v.end()); };
    t.x = x;
    rotate(t.x);
    rotate(t.energy);
    if (!t.force.empty()) rotate(t.force);
}

const BondTableKind& bond_table() {
    static const BondTableKind kind{"r", {{"FP", 2}, {"EQ", 1}}, nullptr, &unit_length, false, &any_range,
                                    &lammps_bond_spline};
    return kind;
}
const BondTableKind& angle_table() {
    static const BondTableKind kind{"theta", {{"FP", 2}, {"EQ", 1}}, nullptr, &unit_degree, false, &angle_range,
                                    &lammps_angle_spline};
    return kind;
}
const BondTableKind& dihedral_table() {
    static const BondTableKind kind{"phi",
                                    {{"NOF", 0}, {"DEGREES", 0}, {"RADIANS", 0}, {"CHECKU", 1}, {"CHECKF", 1}},
                                    &dihedral_columns,
                                    &dihedral_unit,
                                    true,
                                    &dihedral_range,
                                    &lammps_dihedral_spline};
    return kind;
}

TablePoints bond_file_points(const BondTableKind& kind, const TrackedNode& params) {
    const TrackedNode file = params.at("file");
    const std::string path = file.path();
    const LammpsTableSection s =
        read_lammps_table(file.as<std::string>(), params.at("keyword").as<std::string>(), kind.keywords, path, kind.columns);
    for (const char* unsupported : {"CHECKU", "CHECKF"})
        if (s.has(unsupported))
            throw input_error(path, std::string(unsupported) + " (LAMMPS's diagnostic output of the table) is not supported");
    if (s.has("DEGREES") && s.has("RADIANS")) throw input_error(path, "a table is in DEGREES or RADIANS, not both");
    TablePoints t = file_points(s);
    const double unit = kind.file_unit(s);
    for (size_t i = 0; i < t.x.size(); ++i) t.x[i] *= unit;
    for (double& f : t.force) f /= unit;
    read_force_slopes(s, "FP", 1.0 / (unit * unit), path, t);
    check_points(t, path);
    return t;
}

ForceFieldComponent configure_bond(ForceFieldComponent c, const BondTableKind& kind, const ComponentEntry& entry) {
    const int n = table_length(entry);
    const TrackedNode params = input::parameters_of(entry.node);
    const std::string where = entry.node.path() + ".parameters";
    if (!params.valid()) throw input_error(where, "missing: a table needs N and a file or inline points");
    const bool fromFile = params.has("file") || params.has("keyword");
    const bool given = params.has(kind.abscissa) || params.has("energy") || params.has("force");
    if (fromFile == given)
        throw input_error(where, std::string("give the table either from a file (file, keyword) or inline (") +
                                     kind.abscissa + ", energy, force)");
    TablePoints t;
    std::string path;
    if (fromFile) {
        path = params.at("file").path();
        t = bond_file_points(kind, params);
    } else {
        const TrackedNode x = params.at(kind.abscissa);
        path = x.path();
        const std::optional<TrackedNode> force = kind.forceOptional ? params.find("force") : params.at("force");
        t = inline_points(x, params.at("energy"), force ? &*force : nullptr);
    }
    kind.prepare(t, path);
    auto config = std::make_shared<BondTableConfig>();
    config->nodes = kind.resample(t, n);
    config->upper = std::max(t.x.back(), config->nodes.x0 + (config->nodes.n - 1) * config->nodes.delta);
    c.config = config;
    return c;
}

ForceFieldComponent bond_entry(ComponentKey key, int arity, const BondTableKind& kind) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::bond;
    c.arity = arity;
    c.underDomains = arity == 2;  // a tabulated Bond2 reads two positions, which a domain holds
    c.entryParameters = {table_length_parameter()};  // read by configure (bonds read no entry parameters)
    c.configure = [c, &kind](const ComponentEntry& entry, const SystemDescription&) {
        return configure_bond(c, kind, entry);
    };
    return c;
}

}  // namespace

ForceFieldComponent TabulatedPair::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::pair;
    c.entryParameters = {table_length_parameter()};
    c.readsCutOffFactor = false;
    c.actingCutoff = [](const ParameterValues&, const Constants&, double, bool) { return 0.0; };
    c.configure = [c](const ComponentEntry& entry, const SystemDescription& system) {
        return configure_pair(c, entry, system);
    };
    return c;
}

ForceFieldComponent TabulatedBond::reader_entry(ComponentKey key) { return bond_entry(std::move(key), 2, bond_table()); }

ForceFieldComponent TabulatedAngle::reader_entry(ComponentKey key) { return bond_entry(std::move(key), 3, angle_table()); }

ForceFieldComponent TabulatedDihedral::reader_entry(ComponentKey key) {
    return bond_entry(std::move(key), 4, dihedral_table());
}

}  // namespace structmd
