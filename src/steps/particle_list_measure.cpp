#include "steps/particle_list_measure.hpp"

#include <cmath>

#include "core/box.hpp"
#include "core/error.hpp"
#include "forcefield/bonded_geometry.hpp"
#include "input/tracked_node.hpp"

namespace structmd {

namespace {

const char* const kLabels[4] = {"id_i", "id_j", "id_k", "id_l"};

std::string header(int arity, const std::vector<std::array<int64_t, 4>>& ids) {
    static const char* const names[5] = {"", "", "d", "angle", "dihedral"};
    std::string text = "#step time";
    for (const auto& row : ids) {
        text += std::string(" ") + names[arity] + "(";
        for (int k = 0; k < arity; ++k) text += (k ? "," : "") + std::to_string(row[k]);
        text += ")";
    }
    return text;
}

}  // namespace

ParticleListMeasure::ParticleListMeasure(int arity, Layout layout, std::string name, int64_t interval, int64_t start,
                                         int64_t end, std::string outputPath, std::vector<std::array<int64_t, 4>> ids)
    : SimulationStep(name, interval, start, end),
      arity_(arity),
      layout_(layout),
      file_("simulationStep." + name, std::move(outputPath),
            layout == Layout::line ? header(arity, ids) : "# Id_i Id_j distance"),
      ids_(std::move(ids)) {}

void ParticleListMeasure::run(Simulation& sim) {
    std::vector<double> xyz(3 * sim.particle_count());
    sim.get_positions(xyz.data());
    const std::array<double, 3> lengths = sim.box();
    const Box<double> box = Box<double>::make(lengths[0], lengths[1], lengths[2]);
    auto at = [&](int64_t id) { return Vec3<double>{xyz[3 * id], xyz[3 * id + 1], xyz[3 * id + 2]}; };
    std::FILE* out = file_.stream();
    const char* firing = layout_ == Layout::line ? "%lld %.17g" : "# step %lld time %.17g\n";
    std::fprintf(out, firing, static_cast<long long>(sim.current_step()), sim.current_time());
    for (const auto& row : ids_) {
        // Each particle placed at the image nearest the one before it, so the chain is whole.
        Vec3<double> r[4];
        r[0] = at(row[0]);
        for (int k = 1; k < arity_; ++k) r[k] = r[k - 1] + box.minimum_image(at(row[k]) - r[k - 1]);
        double value = 0.0;
        if (arity_ == 2) {
            const Vec3<double> d = r[1] - r[0];
            value = std::sqrt(dot(d, d));
        } else if (arity_ == 3) {
            value = bonded_geometry::bond_angle(r[0] - r[1], r[2] - r[1]).theta;
        } else {
            value = bonded_geometry::dihedral_of(r).phi;
        }
        if (layout_ == Layout::line)
            std::fprintf(out, " %.17g", value);
        else
            std::fprintf(out, "%lld %lld %.17g\n", static_cast<long long>(row[0]), static_cast<long long>(row[1]), value);
    }
    if (layout_ == Layout::line) std::fprintf(out, "\n");
    file_.flush();
}

std::vector<std::array<int64_t, 4>> read_particle_ids(const StepInput& in, const std::vector<std::string>& labels) {
    in.require_all_particles();  // the table names the particles
    const input::Table table = input::read_table(in.node, labels);
    const int64_t n = in.system.numParticles();
    std::vector<std::array<int64_t, 4>> ids;
    for (size_t r = 0; r < table.rows(); ++r) {
        std::array<int64_t, 4> row{0, 0, 0, 0};
        for (size_t k = 0; k < labels.size(); ++k) {
            const input::TrackedNode cell = table.cell(r, labels[k]);
            row[k] = cell.as<int64_t>();
            if (row[k] < 0 || row[k] >= n)
                throw input_error(cell.path(), "particle id " + std::to_string(row[k]) + " does not exist (ids are 0.." +
                                                   std::to_string(n - 1) + ")");
        }
        ids.push_back(row);
    }
    return ids;
}

std::vector<int64_t> read_id_list(const input::TrackedNode& list, int64_t n) {
    if (!list.is_array()) throw input_error(list.path(), "expected a list of particle ids");
    std::vector<int64_t> ids;
    for (size_t k = 0; k < list.size(); ++k) {
        const input::TrackedNode cell = list.at(k);
        const int64_t id = cell.as<int64_t>();
        if (id < 0 || id >= n)
            throw input_error(cell.path(), "particle id " + std::to_string(id) + " does not exist (ids are 0.." +
                                               std::to_string(n - 1) + ")");
        ids.push_back(id);
    }
    return ids;
}

namespace {

template <int Arity, ParticleListMeasure::Layout L>
std::unique_ptr<SimulationStep> make(const StepInput& in) {
    const std::vector<std::array<int64_t, 4>> ids =
        read_particle_ids(in, std::vector<std::string>(kLabels, kLabels + Arity));
    return std::make_unique<ParticleListMeasure>(Arity, L, in.name, in.interval(), in.start(), in.end(),
                                                 in.parameters.text("outputFilePath"), ids);
}

template <int Arity, ParticleListMeasure::Layout L = ParticleListMeasure::Layout::line>
SimulationStepEntry entry(const char* subclass) {
    return {{"ParticlesListMeasure", subclass}, step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make<Arity, L>, std::vector<std::string>(kLabels, kLabels + Arity)};
}

}  // namespace

SimulationStepEntry distances_measure_entry() { return entry<2>("DistancesMeasure"); }
SimulationStepEntry angles_measure_entry() { return entry<3>("AnglesMeasure"); }
SimulationStepEntry dihedrals_measure_entry() { return entry<4>("DihedralsMeasure"); }
SimulationStepEntry contacts_measure_entry() { return entry<2, ParticleListMeasure::Layout::blocks>("ContactsMeasure"); }

}  // namespace structmd
