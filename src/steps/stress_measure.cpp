#include "steps/stress_measure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.hpp"

namespace structmd {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The distinct cells c-1, c, c+1 along an axis of `count` periodic cells (fewer than three when the
// axis has fewer cells, so that no cell is visited twice).
std::vector<int> neighbour_cells(int c, int count) {
    std::vector<int> cells;
    for (int offset = -1; offset <= 1; ++offset) {
        const int k = ((c + offset) % count + count) % count;
        if (std::find(cells.begin(), cells.end(), k) == cells.end()) cells.push_back(k);
    }
    return cells;
}

// Binning of particles into periodic cells at least radiusCutOff wide, so the neighbours of a particle
// lie in its cell and the 26 around it.
struct CellGrid {
    std::array<int, 3> count{};
    std::vector<int64_t> start;     // cell c holds order[start[c] .. start[c+1])
    std::vector<int64_t> order;     // particle indices sorted by cell
    std::vector<std::array<int, 3>> cellOf;

    CellGrid(const std::vector<double>& xyz, const std::array<double, 3>& box, double width) {
        const int64_t n = static_cast<int64_t>(xyz.size() / 3);
        for (int d = 0; d < 3; ++d)
            count[d] = static_cast<int>(std::clamp(std::floor(box[d] / width), 1.0, 1.0e6));
        // A sparse system in a large box would get far more cells than particles; wider cells still
        // hold every neighbour, so halve the counts until the grid is about as large as the system.
        const int64_t most = std::max<int64_t>(64, 2 * n);
        while (static_cast<int64_t>(count[0]) * count[1] * count[2] > most)
            for (int& c : count) c = std::max(1, c / 2);
        cellOf.resize(n);
        std::vector<int64_t> flat(n);
        start.assign(static_cast<size_t>(count[0]) * count[1] * count[2] + 1, 0);
        for (int64_t i = 0; i < n; ++i) {
            for (int d = 0; d < 3; ++d) {
                const double fraction = (xyz[3 * i + d] + 0.5 * box[d]) / box[d];
                cellOf[i][d] = std::clamp(static_cast<int>(std::floor(fraction * count[d])), 0, count[d] - 1);
            }
            flat[i] = index(cellOf[i]);
            ++start[flat[i] + 1];
        }
        for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
        order.resize(n);
        std::vector<int64_t> fill(start.begin(), start.end() - 1);
        for (int64_t i = 0; i < n; ++i) order[fill[flat[i]]++] = i;
    }

    int64_t index(const std::array<int, 3>& c) const {
        return (static_cast<int64_t>(c[2]) * count[1] + c[1]) * count[0] + c[0];
    }
};

}  // namespace

std::vector<double> neighbour_volumes(const std::vector<double>& xyz, const std::array<double, 3>& box,
                                      double radiusCutOff) {
    const int64_t n = static_cast<int64_t>(xyz.size() / 3);
    const CellGrid grid(xyz, box, radiusCutOff);
    const double cutoff2 = radiusCutOff * radiusCutOff;
    std::vector<double> volumes(n, 0.0);
    for (int64_t i = 0; i < n; ++i) {
        double inverseSum = 0.0;
        double inverseSquareSum = 0.0;
        const std::array<int, 3>& home = grid.cellOf[i];
        for (int cz : neighbour_cells(home[2], grid.count[2]))
            for (int cy : neighbour_cells(home[1], grid.count[1]))
                for (int cx : neighbour_cells(home[0], grid.count[0])) {
                    const int64_t c = grid.index({cx, cy, cz});
                    for (int64_t k = grid.start[c]; k < grid.start[c + 1]; ++k) {
                        const int64_t j = grid.order[k];
                        if (j == i) continue;
                        double r2 = 0.0;
                        for (int d = 0; d < 3; ++d) {
                            double delta = xyz[3 * j + d] - xyz[3 * i + d];
                            delta -= box[d] * std::round(delta / box[d]);
                            r2 += delta * delta;
                        }
                        if (r2 >= cutoff2) continue;
                        inverseSum += 1.0 / std::sqrt(r2);
                        inverseSquareSum += 1.0 / r2;
                    }
                }
        if (inverseSquareSum > 0.0) {
            const double radius = 0.5 * inverseSum / inverseSquareSum;
            volumes[i] = 4.0 / 3.0 * kPi * radius * radius * radius;
        }
    }
    return volumes;
}

StressMeasure::StressMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                             double radiusCutOff, std::vector<uint8_t> members)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), "#id volume sxx sxy sxz syx syy syz szx szy szz"),
      radiusCutOff_(radiusCutOff),
      members_(std::move(members)) {}

void StressMeasure::run(Simulation& sim) {
    const std::array<double, 3> box = sim.box();
    const double halfBox = 0.5 * std::min({box[0], box[1], box[2]});
    // The box can shrink after load (structmd_set_box); past half the box a pair has two images.
    if (radiusCutOff_ >= halfBox) {
        std::ostringstream what;
        what << "simulationStep." << name() << ".parameters.radiusCutOff: " << radiusCutOff_
             << " is not shorter than half the box (" << halfBox << ") at step " << sim.current_step();
        throw Error(STRUCTMD_ERR_STATE, what.str());
    }
    const int64_t n = sim.particle_count();
    std::vector<double> xyz(3 * n);
    sim.get_positions(xyz.data());
    std::vector<double> virials(9 * n);
    sim.get_pair_virials(virials.data());
    const std::vector<double> volumes = neighbour_volumes(xyz, box, radiusCutOff_);

    std::FILE* out = file_.stream();
    std::fprintf(out, "#step %lld\n", static_cast<long long>(sim.current_step()));
    for (int64_t i = 0; i < n; ++i) {
        if (!members_.empty() && !members_[i]) continue;
        std::fprintf(out, "%lld %.10g", static_cast<long long>(i), volumes[i]);
        for (int k = 0; k < 9; ++k) {
            const double s = virials[9 * i + k];
            const double stress = volumes[i] > 0.0 ? s / volumes[i]
                                  : s == 0.0       ? 0.0
                                                   : std::numeric_limits<double>::quiet_NaN();
            std::fprintf(out, " %.10g", stress);
        }
        std::fputc('\n', out);
    }
    file_.flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    const double radius = in.parameters.number("radiusCutOff");
    const auto& box = in.system.box;
    const double halfBox = 0.5 * std::min({box[0], box[1], box[2]});
    if (radius >= halfBox) {
        std::ostringstream what;
        what << "radiusCutOff " << radius << " is not shorter than half the box (" << halfBox << ")";
        throw input_error(in.parameters.path("radiusCutOff"), what.str());
    }
    return std::make_unique<StressMeasure>(in.name, in.interval(), in.start(), in.end(),
                                           in.parameters.text("outputFilePath"), radius, in.members);
}

}  // namespace

SimulationStepEntry stress_measure_entry() {
    return {{"MechanicalMeasure", "StressMeasure"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr},
                             {"radiusCutOff", StepValue::number, nullptr, Must::be_positive, "length",
                              "shorter than half the shortest box edge"}}),
            make};
}

}  // namespace structmd
