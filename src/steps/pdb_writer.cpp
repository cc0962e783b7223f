#include "steps/pdb_writer.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <vector>

#include "steps/chemical_elements.hpp"
#include "steps/text_trajectory_writer.hpp"

namespace structmd {

namespace {

// PDB: MODEL, CRYST1, one ATOM record per particle, ENDMDL. No END record, so that frames can be
// appended. ATOM: serial id+1 modulo 100000, the type name as atom name, residue UNK numbered by the
// structure's resId (modulo 10000; 1 without it), chain letter by its chainId (kChainLetters
// cyclically; A without it), element the type name when it is one, else X (ASE's unknown element,
// which its reader needs for coarse-grained names). The fixed columns hold coordinates from -999.999
// to 9999.999; larger ones widen the line. The first model of a file carries CONECT records for the two-particle bonds
// among the particles written, the one place VMD, MDAnalysis and others read bonds from in a
// multi-model file, when serials are unambiguous (every id below 99999).
class PdbWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;

protected:
    void count_existing_frames() override {
        std::unique_ptr<std::FILE, int (*)(std::FILE*)> existing(std::fopen(options().path.c_str(), "r"), &std::fclose);
        if (!existing) return;
        int64_t models = 0;
        char line[128];
        bool lineStart = true;
        while (std::fgets(line, sizeof line, existing.get())) {
            if (lineStart && std::strncmp(line, "MODEL ", 6) == 0) ++models;
            lineStart = std::strchr(line, '\n') != nullptr;
        }
        set_frames(models);
    }

    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        const auto& L = frame.box;
        const MoleculeLayout& molecules = options().molecules;
        std::fprintf(f, "MODEL     %4lld\n", static_cast<long long>(frames() + 1));
        std::fprintf(f, "CRYST1%9.3f%9.3f%9.3f%7.2f%7.2f%7.2f %-11s%4d\n", L[0], L[1], L[2], 90.0, 90.0, 90.0, "P 1", 1);
        for (size_t i = 0; i < frame.types.size(); ++i) {
            const auto id = static_cast<size_t>(frame.ids[i]);
            const char chain = molecules.chain.empty() ? 'A' : chain_letter(molecules.chain[id]);
            const int residue = molecules.residue.empty() ? 1 : wrapped_residue(molecules.residue[id]);
            const std::string& name = frame.typeNames[frame.types[i]];
            std::fprintf(f, "ATOM  %5d %-4.4s UNK %c%4d    %8.3f%8.3f%8.3f%6.2f%6.2f          %2s\n",
                         serial(frame.ids[i]), name.c_str(), chain, residue, frame.positions[3 * i],
                         frame.positions[3 * i + 1], frame.positions[3 * i + 2], 1.0, 0.0,
                         atomic_number(name) > 0 ? name.c_str() : "X");
        }
        if (frames() == 0) write_connections(f, frame);
        std::fprintf(f, "ENDMDL\n");
    }

private:
    static constexpr const char* kChainLetters = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    static constexpr int64_t kSerials = 100000;

    static int serial(int64_t id) { return static_cast<int>((id + 1) % kSerials); }
    static char chain_letter(int32_t chain) {
        const auto count = static_cast<int32_t>(std::strlen(kChainLetters));
        return kChainLetters[((chain % count) + count) % count];
    }
    static int wrapped_residue(int32_t residue) { return ((residue % 10000) + 10000) % 10000; }

    // CONECT records: each particle with its bonded partners among those written, four per record.
    void write_connections(std::FILE* f, const TrajectoryFrame& frame) const {
        const std::vector<std::array<int64_t, 2>>& bonds = options().molecules.bonds;
        if (bonds.empty() || frame.ids.empty() || frame.ids.back() + 1 >= kSerials) return;
        auto written = [&](int64_t id) { return std::binary_search(frame.ids.begin(), frame.ids.end(), id); };
        std::map<int64_t, std::vector<int64_t>> partners;
        for (const auto& [i, j] : bonds) {
            if (!written(i) || !written(j)) continue;
            partners[i].push_back(j);
            partners[j].push_back(i);
        }
        for (auto& [id, others] : partners) {
            std::sort(others.begin(), others.end());
            for (size_t k = 0; k < others.size(); k += 4) {
                std::fprintf(f, "CONECT%5d", serial(id));
                for (size_t m = k; m < std::min(k + 4, others.size()); ++m) std::fprintf(f, "%5d", serial(others[m]));
                std::fprintf(f, "\n");
            }
        }
    }
};

}  // namespace

std::unique_ptr<TrajectoryWriter> make_pdb_writer(TrajectoryOptions options) {
    return std::make_unique<PdbWriter>(std::move(options));
}

}  // namespace structmd
