#include "steps/stress_measure.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/box.hpp"
#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "neighbour/cell_grid.hpp"

namespace structmd {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The particles binned into the engine's cell grid (cells at least radiusCutOff wide, so the
// neighbours of a particle lie in its cell and the ones adjacent), in index order within each cell.
struct BinnedParticles {
    Box<double> box;
    CellGrid<double> grid;
    std::vector<int> cellOf;     // by particle
    std::vector<int64_t> start;  // cell c holds order[start[c] .. start[c+1])
    std::vector<int64_t> order;  // particle indices sorted by cell

    BinnedParticles(const std::vector<double>& xyz, const std::array<double, 3>& lengths, double width)
        : box(Box<double>::make(lengths[0], lengths[1], lengths[2])) {
        const int64_t n = static_cast<int64_t>(xyz.size() / 3);
        grid = CellGrid<double>::make(box, width, n);
        cellOf.resize(n);
        start.assign(static_cast<size_t>(grid.count()) + 1, 0);
        for (int64_t i = 0; i < n; ++i) {
            int cx, cy, cz;
            grid.coordinates({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, box, cx, cy, cz);
            cellOf[i] = grid.index(cx, cy, cz);
            ++start[cellOf[i] + 1];
        }
        for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
        order.resize(n);
        std::vector<int64_t> fill(start.begin(), start.end() - 1);
        for (int64_t i = 0; i < n; ++i) order[fill[cellOf[i]]++] = i;
    }
};

}  // namespace

std::vector<double> neighbour_volumes(const std::vector<double>& xyz, const std::array<double, 3>& box,
                                      double radiusCutOff) {
    const int64_t n = static_cast<int64_t>(xyz.size() / 3);
    const BinnedParticles binned(xyz, box, radiusCutOff);
    const CellGrid<double>& grid = binned.grid;
    const double cutoff2 = radiusCutOff * radiusCutOff;
    std::vector<double> volumes(n, 0.0);
    for (int64_t i = 0; i < n; ++i) {
        double inverseSum = 0.0;
        double inverseSquareSum = 0.0;
        int cx, cy, cz;
        grid.coordinates({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, binned.box, cx, cy, cz);
        grid.for_each_adjacent(cx, cy, cz, 0, [&](int c) {
            for (int64_t k = binned.start[c]; k < binned.start[c + 1]; ++k) {
                const int64_t j = binned.order[k];
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
        });
        if (inverseSquareSum > 0.0) {
            const double radius = 0.5 * inverseSum / inverseSquareSum;
            volumes[i] = 4.0 / 3.0 * kPi * radius * radius * radius;
        }
    }
    return volumes;
}

StressMeasure::StressMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                             double radiusCutOff, std::vector<uint8_t> members)
    : GroupMeasureStep(std::move(name), interval, start, end, std::move(outputPath),
                       "#id volume sxx sxy sxz syx syy syz szx szy szz", std::move(members)),
      radiusCutOff_(radiusCutOff) {}

void StressMeasure::run(Simulation& sim) {
    const std::array<double, 3> box = sim.box();
    // The box can also be made open after load (structmd_set_box); the cells need a length.
    if (has_open_axis(box[0], box[1], box[2]))
        throw Error(STRUCTMD_ERR_STATE, "simulationStep." + name() + ": the box has an open axis at step " +
                                            std::to_string(sim.current_step()) + "; the stress measure's cells need a "
                                            "periodic box");
    const double halfBox = half_shortest_edge(box[0], box[1], box[2]);
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

    std::FILE* out = file().stream();
    std::fprintf(out, "#step %lld\n", static_cast<long long>(sim.current_step()));
    for (int64_t i = 0; i < n; ++i) {
        if (!measured(i)) continue;
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
    file().flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    const double radius = in.parameters.number("radiusCutOff");
    const auto& box = in.system.box;
    require_periodic_box({box[0], box[1], box[2]}, in.path + ".type", "[\"MechanicalMeasure\", \"StressMeasure\"]'s cells");
    const double halfBox = half_shortest_edge(box[0], box[1], box[2]);
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
