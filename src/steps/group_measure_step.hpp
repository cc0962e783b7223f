#pragma once
// What the measures over a group of particles share (centre of mass, gyration radius, mean square
// displacement, ...): the text file each writes and the group's member mask.
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"

namespace structmd {

class GroupMeasureStep : public SimulationStep {
public:
    // header: the file's first line. members: by particle id, 1 for the particles measured; empty for
    // every particle.
    GroupMeasureStep(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                     std::string header, std::vector<uint8_t> members)
        : SimulationStep(name, interval, start, end),
          file_("simulationStep." + name, std::move(outputPath), std::move(header)),
          members_(std::move(members)) {}

protected:
    bool measured(int64_t id) const { return members_.empty() || members_[static_cast<size_t>(id)]; }
    MeasureFile& file() { return file_; }
    // Writes the line `step time v1 v2 ...`, every number to the digits that read back the same double.
    void write_line(const Simulation& sim, std::initializer_list<double> values) {
        std::FILE* out = file_.stream();
        std::fprintf(out, "%lld %.17g", static_cast<long long>(sim.current_step()), sim.current_time());
        for (double v : values) std::fprintf(out, " %.17g", v);
        std::fputc('\n', out);
        file_.flush();
    }

private:
    MeasureFile file_;
    std::vector<uint8_t> members_;
};

}  // namespace structmd
