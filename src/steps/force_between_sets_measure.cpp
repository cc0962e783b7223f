#include "steps/force_between_sets_measure.hpp"

#include <array>

#include "core/error.hpp"
#include "input/read_parameters.hpp"
#include "input/tracked_node.hpp"
#include "steps/particle_list_measure.hpp"

namespace structmd {

ForceBetweenSetsMeasure::ForceBetweenSetsMeasure(std::string name, int64_t interval, int64_t start, int64_t end,
                                                 std::string outputPath, std::vector<Set> sets)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), "#From To Fx Fy Fz"),
      sets_(std::move(sets)) {}

void ForceBetweenSetsMeasure::run(Simulation& sim) {
    const size_t count = sets_.size();
    // on[to][from]: the force set `from` exerts on set `to`.
    std::vector<std::vector<std::array<double, 3>>> on(count, std::vector<std::array<double, 3>>(count, {0, 0, 0}));
    std::vector<double> f(3 * sim.particle_count());
    for (size_t to = 0; to < count; ++to)
        for (int64_t i : sets_[to].ids) {
            sim.probes().pair_forces_on(i, f.data());
            for (size_t from = 0; from < count; ++from) {
                if (from == to) continue;
                for (int64_t j : sets_[from].ids)
                    for (int a = 0; a < 3; ++a) on[to][from][a] += f[3 * j + a];
            }
        }
    std::FILE* out = file_.stream();
    std::fprintf(out, "# step %lld time %.17g\n", static_cast<long long>(sim.current_step()), sim.current_time());
    for (size_t to = 0; to < count; ++to)
        for (size_t from = 0; from < count; ++from)
            if (from != to)
                std::fprintf(out, "%s %s %.17g %.17g %.17g\n", sets_[from].name.c_str(), sets_[to].name.c_str(),
                             on[to][from][0], on[to][from][1], on[to][from][2]);
    file_.flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    in.require_all_particles();  // the table names the particles
    const input::Table table = input::read_table(in.node, {"name", "id_list"});
    const int64_t n = in.system.numParticles();
    std::vector<ForceBetweenSetsMeasure::Set> sets;
    for (size_t r = 0; r < table.rows(); ++r) {
        ForceBetweenSetsMeasure::Set set;
        const input::TrackedNode nameCell = table.cell(r, "name");
        set.name = nameCell.as<std::string>();
        for (const ForceBetweenSetsMeasure::Set& other : sets)
            if (other.name == set.name) throw input_error(nameCell.path(), "a second set named '" + set.name + "'");
        const input::TrackedNode list = table.cell(r, "id_list");
        set.ids = read_id_list(list, n);
        sets.push_back(std::move(set));
    }
    return std::make_unique<ForceBetweenSetsMeasure>(in.name, in.interval(), in.start(), in.end(),
                                                     in.parameters.text("outputFilePath"), std::move(sets));
}

}  // namespace

SimulationStepEntry force_between_sets_measure_entry() {
    return {{"MechanicalMeasure", "ForceBetweenSetsMeasure"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make,
            {"name", "id_list"}};
}

}  // namespace structmd
