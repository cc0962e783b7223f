#pragma once
// Reading one section of a table file in LAMMPS's format (pair_style, bond_style, angle_style and
// dihedral_style table):
//
//   # comments and blank lines anywhere
//   KEYWORD                      the section's name, the first word of its line
//   N 500 FP 0.0 0.0 EQ 1.0      the parameter line: N and the style's own keywords with their values
//                                (blank line)
//   1 x1 energy1 force1          N rows: index (1..N), abscissa, energy, force ("index x energy" for
//   ...                           dihedral tables with NOF)
//
// Sections before the one asked for are skipped by their N, as LAMMPS does. Unlike LAMMPS, which warns
// and carries on, every defect is an input error naming the JSON path that named the file and the
// file's line: no such section, a parameter line without N or with an unknown keyword, a row with the
// wrong number of fields, a field that is not a number, an index out of order, fewer rows than N, or
// a row numbered N + 1 right after the N rows (N smaller than the table).
#include <map>
#include <string>
#include <vector>

namespace structmd {

struct LammpsTableSection {
    int n = 0;
    // The parameter line's keywords but N, each with the words after it.
    std::map<std::string, std::vector<std::string>> keywords;
    std::vector<double> x, energy, force;  // the rows' columns (force empty for 3-column rows)

    bool has(const std::string& keyword) const { return keywords.count(keyword) > 0; }
    // The keyword's k-th value as a number; an input error at `path` if it is not one.
    double number(const std::string& keyword, size_t k, const std::string& path) const;
};

// `accepted`: the keywords the style allows on the parameter line, each with its number of values
// (N is always accepted). `columns(section)`: the fields of each row (4, or 3 for dihedral NOF).
// Relative file names are taken from the current working directory.
LammpsTableSection read_lammps_table(const std::string& file, const std::string& keyword,
                                     const std::map<std::string, int>& accepted, const std::string& path,
                                     int (*columns)(const LammpsTableSection&) = nullptr);

}  // namespace structmd
