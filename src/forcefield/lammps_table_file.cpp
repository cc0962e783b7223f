#include "forcefield/lammps_table_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.hpp"
#include "core/regular_file.hpp"

namespace structmd {

namespace {

// The file's lines as words, comments (from '#') removed, blank lines kept out but their numbers kept.
struct Line {
    int number;
    std::vector<std::string> words;
};

std::vector<Line> read_lines(const std::string& file, const std::string& path) {
    const FileContents contents = read_regular_file(file);
    if (!contents.problem.empty()) throw input_error(path, "table file '" + file + "': " + contents.problem);
    std::istringstream in(contents.bytes);
    std::vector<Line> lines;
    std::string text;
    for (int number = 1; std::getline(in, text); ++number) {
        const size_t hash = text.find('#');
        if (hash != std::string::npos) text.erase(hash);
        std::istringstream words(text);
        Line line{number, {}};
        for (std::string w; words >> w;) line.words.push_back(w);
        if (!line.words.empty()) lines.push_back(std::move(line));
    }
    return lines;
}

// A finite number: strtod also reads "nan" and "inf", which no table means (FPRIME nan 0 loaded and
// gave NaN energies).
bool parse_double(const std::string& word, double& value) {
    errno = 0;
    char* end = nullptr;
    value = std::strtod(word.c_str(), &end);
    return end != word.c_str() && *end == '\0' && errno != ERANGE && std::isfinite(value);
}

bool parse_int(const std::string& word, long& value) {
    errno = 0;
    char* end = nullptr;
    value = std::strtol(word.c_str(), &end, 10);
    return end != word.c_str() && *end == '\0' && errno != ERANGE;
}

class Reader {
public:
    Reader(std::string file, std::string path) : file_(std::move(file)), path_(std::move(path)) {}

    [[noreturn]] void fail(const Line& line, const std::string& what) const {
        throw input_error(path_, file_ + ":" + std::to_string(line.number) + ": " + what);
    }

    LammpsTableSection parameters(const Line& line, const std::map<std::string, int>& accepted) const {
        LammpsTableSection section;
        const std::vector<std::string>& w = line.words;
        for (size_t k = 0; k < w.size();) {
            if (w[k] == "N") {
                long n = 0;
                if (k + 1 >= w.size() || !parse_int(w[k + 1], n) || n < 2)
                    fail(line, "N must be followed by the number of rows (at least 2)");
                section.n = static_cast<int>(n);
                k += 2;
                continue;
            }
            const auto known = accepted.find(w[k]);
            if (known == accepted.end()) {
                std::string names = "N";
                for (const auto& [name, count] : accepted) names += ", " + name;
                fail(line, "unknown keyword '" + w[k] + "' on the parameter line (this style accepts " + names + ")");
            }
            if (k + known->second >= w.size())
                fail(line, "keyword " + w[k] + " needs " + std::to_string(known->second) + " value(s)");
            section.keywords[w[k]] = std::vector<std::string>(w.begin() + k + 1, w.begin() + k + 1 + known->second);
            k += 1 + known->second;
        }
        if (section.n == 0) fail(line, "the parameter line does not set N");
        return section;
    }

private:
    std::string file_, path_;
};

}  // namespace

double LammpsTableSection::number(const std::string& keyword, size_t k, const std::string& path) const {
    double value = 0;
    const std::vector<std::string>& values = keywords.at(keyword);
    if (k >= values.size() || !parse_double(values[k], value))
        throw input_error(path, "keyword " + keyword + ": expected a number, got '" +
                                    (k < values.size() ? values[k] : std::string()) + "'");
    return value;
}

LammpsTableSection read_lammps_table(const std::string& file, const std::string& keyword,
                                     const std::map<std::string, int>& accepted, const std::string& path,
                                     int (*columns)(const LammpsTableSection&)) {
    const std::vector<Line> lines = read_lines(file, path);
    const Reader reader(file, path);
    size_t k = 0;
    // Find the section: a line whose first word is the keyword; other sections are skipped by their N.
    while (true) {
        if (k >= lines.size()) throw input_error(path, "table file '" + file + "' has no section '" + keyword + "'");
        if (lines[k].words[0] == keyword) break;
        if (k + 1 >= lines.size()) reader.fail(lines[k], "section '" + lines[k].words[0] + "' has no parameter line");
        // Skipping: only N matters, whatever the other keywords are.
        const std::vector<std::string>& w = lines[k + 1].words;
        long n = -1;
        for (size_t m = 0; m + 1 < w.size(); ++m)
            if (w[m] == "N" && parse_int(w[m + 1], n)) break;
        if (n < 0) reader.fail(lines[k + 1], "the parameter line of section '" + lines[k].words[0] + "' does not set N");
        k += 2 + static_cast<size_t>(n);
    }
    const Line& keywordLine = lines[k];
    if (keywordLine.words.size() != 1) reader.fail(keywordLine, "a section's name line has one word only");
    if (k + 1 >= lines.size()) reader.fail(keywordLine, "section '" + keyword + "' has no parameter line");
    LammpsTableSection section = reader.parameters(lines[k + 1], accepted);
    const size_t fields = columns ? static_cast<size_t>(columns(section)) : 4u;
    k += 2;
    for (int row = 0; row < section.n; ++row, ++k) {
        if (k >= lines.size())
            throw input_error(path, file + ": section '" + keyword + "' has N = " + std::to_string(section.n) +
                                        " but only " + std::to_string(row) + " rows");
        const Line& line = lines[k];
        if (line.words.size() != fields)
            reader.fail(line, "expected " + std::to_string(fields) + " fields (index, x, energy" +
                                  (fields == 4 ? ", force" : "") + "), got " + std::to_string(line.words.size()));
        long index = 0;
        if (!parse_int(line.words[0], index) || index != row + 1)
            reader.fail(line, "expected row index " + std::to_string(row + 1) + ", got '" + line.words[0] + "'");
        double v[3] = {0, 0, 0};
        for (size_t f = 1; f < fields; ++f)
            if (!parse_double(line.words[f], v[f - 1]))
                reader.fail(line, "field " + std::to_string(f + 1) + " is not a number: '" + line.words[f] + "'");
        section.x.push_back(v[0]);
        section.energy.push_back(v[1]);
        if (fields == 4) section.force.push_back(v[2]);
    }
    if (k < lines.size()) {
        long index = 0;
        if (lines[k].words.size() == fields && parse_int(lines[k].words[0], index) && index == section.n + 1)
            reader.fail(lines[k], "section '" + keyword + "' has more rows than its N = " + std::to_string(section.n));
    }
    return section;
}

}  // namespace structmd
