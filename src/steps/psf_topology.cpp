#include "steps/psf_topology.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <unordered_map>

#include "core/error.hpp"

namespace structmd {

namespace {

constexpr size_t kNameLength = 7;      // VMD's PSF reader takes at most 7 characters of a word
constexpr int32_t kSegments = 1000000;  // "S" and six digits
constexpr int32_t kResidues = 10000000;  // seven digits

int32_t wrapped(int32_t value, int32_t modulus) { return ((value % modulus) + modulus) % modulus; }

std::string psf_word(const std::string& name) {
    std::string word = name.substr(0, kNameLength);
    std::replace_if(word.begin(), word.end(), [](unsigned char c) { return c <= ' '; }, '_');
    return word.empty() ? "X" : word;
}

template <typename T>
T value_of(const std::vector<T>& byId, int64_t id, T otherwise) {
    return id >= 0 && static_cast<size_t>(id) < byId.size() ? byId[static_cast<size_t>(id)] : otherwise;
}

// The rows whose every particle is in the frame, as serials (1 + position in the frame).
template <size_t Arity>
std::vector<std::array<int64_t, Arity>> serials_of(const std::vector<std::array<int64_t, Arity>>& rows,
                                                   const std::unordered_map<int64_t, int64_t>& serial) {
    std::vector<std::array<int64_t, Arity>> kept;
    for (const auto& row : rows) {
        std::array<int64_t, Arity> serials{};
        bool inFrame = true;
        for (size_t k = 0; k < Arity && inFrame; ++k) {
            const auto at = serial.find(row[k]);
            inFrame = at != serial.end();
            if (inFrame) serials[k] = at->second;
        }
        if (inFrame) kept.push_back(serials);
    }
    return kept;
}

template <size_t Arity>
void write_section(std::FILE* f, const std::vector<std::array<int64_t, Arity>>& rows, size_t perLine,
                   const char* title) {
    std::fprintf(f, "\n%10zu !%s\n", rows.size(), title);
    for (size_t r = 0; r < rows.size(); ++r) {
        for (int64_t serial : rows[r]) std::fprintf(f, "%10lld", static_cast<long long>(serial));
        if ((r + 1) % perLine == 0 || r + 1 == rows.size()) std::fprintf(f, "\n");
    }
}

}  // namespace

void write_psf_topology(const std::string& path, const std::string& owner, const TrajectoryFrame& frame,
                        const MoleculeLayout& molecules) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "w"), &std::fclose);
    const auto failed = [&](const char* action) {
        return Error(STRUCTMD_ERR_IO, owner + ": cannot " + action + " the DCD's topology '" + path +
                                          "': " + (errno ? std::strerror(errno) : "short write"));
    };
    errno = 0;
    if (!file) throw failed("open");
    std::FILE* f = file.get();

    std::unordered_map<int64_t, int64_t> serial;
    serial.reserve(frame.ids.size());
    for (size_t i = 0; i < frame.ids.size(); ++i) serial.emplace(frame.ids[i], static_cast<int64_t>(i) + 1);

    std::fprintf(f, "PSF EXT NAMD\n\n%10d !NTITLE\n", 2);
    std::fprintf(f, " REMARKS written by structmd " STRUCTMD_VERSION_STRING "\n");
    std::fprintf(f, " REMARKS topology of the DCD trajectory of %s\n", owner.c_str());
    std::fprintf(f, "\n%10zu !NATOM\n", frame.ids.size());
    for (size_t i = 0; i < frame.ids.size(); ++i) {
        const int64_t id = frame.ids[i];
        const std::string name = psf_word(frame.typeNames.at(static_cast<size_t>(frame.types[i])));
        std::fprintf(f, "%10zu S%-7d %-8d UNK      %-8s %-8s %14.6g %14.6g %11d\n", i + 1,
                     wrapped(value_of<int32_t>(molecules.chain, id, 0), kSegments),
                     wrapped(value_of<int32_t>(molecules.residue, id, 1), kResidues),
                     name.c_str(), name.c_str(), value_of(molecules.charge, id, 0.0),
                     value_of(molecules.mass, id, 0.0), 0);
    }
    write_section(f, serials_of(molecules.bonds, serial), 4, "NBOND: bonds");
    write_section(f, serials_of(molecules.angles, serial), 3, "NTHETA: angles");
    write_section(f, serials_of(molecules.dihedrals, serial), 2, "NPHI: dihedrals");
    write_section(f, std::vector<std::array<int64_t, 4>>{}, 2, "NIMPHI: impropers");
    write_section(f, std::vector<std::array<int64_t, 2>>{}, 4, "NDON: donors");
    write_section(f, std::vector<std::array<int64_t, 2>>{}, 4, "NACC: acceptors");
    std::fprintf(f, "\n%10d !NNB\n\n", 0);
    if (std::ferror(f) || std::fflush(f) != 0) throw failed("write");
}

}  // namespace structmd
