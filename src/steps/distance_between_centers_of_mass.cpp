#include "steps/distance_between_centers_of_mass.hpp"

#include <array>
#include <cmath>

#include "core/error.hpp"
#include "input/tracked_node.hpp"
#include "steps/particle_list_measure.hpp"

namespace structmd {

namespace {

std::string header(size_t pairs) {
    std::string text = "#step time";
    for (size_t p = 0; p < pairs; ++p) text += " distance_" + std::to_string(p);
    return text;
}

// The image of d nearest the origin, in a box of edges L.
std::array<double, 3> minimum_image(std::array<double, 3> d, const std::array<double, 3>& L) {
    for (int a = 0; a < 3; ++a) d[a] -= L[a] * std::round(d[a] / L[a]);
    return d;
}

// The centre of the set `ids` (set_interaction.hpp's rule), from the wrapped positions and masses.
std::array<double, 3> centre_of(Simulation& sim, const std::vector<int64_t>& ids, const std::vector<double>& mass,
                                const std::array<double, 3>& L) {
    std::vector<double> xyz(3 * ids.size());
    sim.get_positions_of(ids.data(), static_cast<int64_t>(ids.size()), xyz.data());
    std::array<double, 3> weighted{0, 0, 0}, plain{0, 0, 0};
    double total = 0.0;
    for (size_t k = 0; k < ids.size(); ++k) {
        const std::array<double, 3> d =
            minimum_image({xyz[3 * k] - xyz[0], xyz[3 * k + 1] - xyz[1], xyz[3 * k + 2] - xyz[2]}, L);
        for (int a = 0; a < 3; ++a) {
            weighted[a] += mass[ids[k]] * (xyz[a] + d[a]);
            plain[a] += xyz[a] + d[a];
        }
        total += mass[ids[k]];
    }
    for (int a = 0; a < 3; ++a)
        weighted[a] = total > 0.0 ? weighted[a] / total : plain[a] / static_cast<double>(ids.size());
    return weighted;
}

}  // namespace

DistanceBetweenCentersOfMass::DistanceBetweenCentersOfMass(std::string name, int64_t interval, int64_t start,
                                                           int64_t end, std::string outputPath,
                                                           std::vector<Pair> pairs)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), header(pairs.size())),
      pairs_(std::move(pairs)) {}

void DistanceBetweenCentersOfMass::run(Simulation& sim) {
    std::vector<double> mass(sim.particle_count());
    sim.get_masses(mass.data());
    const std::array<double, 3> L = sim.box();
    std::FILE* out = file_.stream();
    std::fprintf(out, "%lld %.17g", static_cast<long long>(sim.current_step()), sim.current_time());
    for (const Pair& pair : pairs_) {
        const std::array<double, 3> a = centre_of(sim, pair.first, mass, L);
        const std::array<double, 3> b = centre_of(sim, pair.second, mass, L);
        const std::array<double, 3> d = minimum_image({a[0] - b[0], a[1] - b[1], a[2] - b[2]}, L);
        std::fprintf(out, " %.17g", std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
    std::fprintf(out, "\n");
    file_.flush();
}

namespace {

std::vector<int64_t> ids_of(const input::TrackedNode& list, int64_t n) {
    if (!list.is_array() || list.size() == 0) throw input_error(list.path(), "expected a non-empty list of particle ids");
    return read_id_list(list, n);
}

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    in.require_all_particles();  // the table names the particles
    const input::Table table = input::read_table(in.node, {"idSet_i", "idSet_j"});
    const int64_t n = in.system.numParticles();
    std::vector<DistanceBetweenCentersOfMass::Pair> pairs;
    for (size_t r = 0; r < table.rows(); ++r)
        pairs.push_back({ids_of(table.cell(r, "idSet_i"), n), ids_of(table.cell(r, "idSet_j"), n)});
    return std::make_unique<DistanceBetweenCentersOfMass>(in.name, in.interval(), in.start(), in.end(),
                                                          in.parameters.text("outputFilePath"), std::move(pairs));
}

}  // namespace

SimulationStepEntry distance_between_centers_of_mass_entry() {
    return {{"GeometricalMeasure", "DistanceBetweenCentersOfMass"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make,
            {"idSet_i", "idSet_j"}};
}

}  // namespace structmd
