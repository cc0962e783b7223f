#include "steps/write_patchy_particles_step.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace structmd {

WritePatchyParticlesStep::WritePatchyParticlesStep(std::string name, int64_t interval, int64_t start, int64_t end,
                                                   bool wrapped, std::vector<uint8_t> members,
                                                   std::unique_ptr<TrajectoryWriter> writer,
                                                   std::vector<std::shared_ptr<const PatchyConfig>> patchy,
                                                   std::vector<int> firstType, std::vector<std::string> typeNames)
    : WriteStep(std::move(name), interval, start, end, wrapped, std::move(members), std::move(writer),
                std::move(typeNames)),
      patchy_(std::move(patchy)),
      firstType_(std::move(firstType)) {}

void WritePatchyParticlesStep::append(Simulation& sim, const std::vector<double>& positions, TrajectoryFrame& frame) {
    const int64_t n = sim.particle_count();
    orientations_.resize(4 * n);
    sim.get_orientations(orientations_.data());
    int64_t id = n;
    for (size_t e = 0; e < patchy_.size(); ++e) {
        const PatchyConfig& config = *patchy_[e];
        for (size_t a = 0; a < config.parent.size(); ++a, ++id) {
            const int p = config.parent[a];
            if (!written(p)) continue;
            const double* q = &orientations_[4 * p];
            const Real4<double> dir{q[0], q[1], q[2], q[3]};
            const Vec3<double> x = Vec3<double>{positions[3 * p], positions[3 * p + 1], positions[3 * p + 2]} +
                                   patch_math::apply(patch_math::frame_of(dir), config.offset[a]);
            frame.ids.push_back(id);
            frame.positions.insert(frame.positions.end(), {x.x, x.y, x.z});
            frame.types.push_back(firstType_[e] + config.type[a]);
            frame.radii.push_back(config.typeRadius[config.type[a]]);
        }
    }
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    std::unique_ptr<TrajectoryWriter> writer = trajectory_writer_of(in);
    if (writer->needs_velocities() || writer->needs_forces() || writer->needs_orientations() || writer->needs_moments())
        throw input_error(in.parameters.path("outputFormat"),
                          "patches have positions, types and radii only: choose a format that writes no velocities, "
                          "forces, orientations or magnetic moments (as sp, xyz, coord, lammpstrj, dcd)");
    // UAMMD-structured takes its patchy entries in the order of their names.
    std::vector<const ExternalSpec*> entries;
    for (const ExternalSpec& external : in.forceField.externals)
        if (external.key.cls == "PatchyParticles") entries.push_back(&external);
    std::sort(entries.begin(), entries.end(), [](const ExternalSpec* a, const ExternalSpec* b) { return a->name < b->name; });
    if (entries.empty()) in.log.warning(in.path + ": no [\"PatchyParticles\", ...] entry: only the particles are written");
    std::vector<std::string> typeNames;
    for (const auto& type : in.system.types) typeNames.push_back(type.name);
    std::vector<std::shared_ptr<const PatchyConfig>> patchy;
    std::vector<int> firstType;
    for (const ExternalSpec* entry : entries) {
        auto config = std::static_pointer_cast<const PatchyConfig>(entry->config);
        typeNames.push_back("");
        firstType.push_back(static_cast<int>(typeNames.size()));
        typeNames.insert(typeNames.end(), config->typeNames.begin(), config->typeNames.end());
        patchy.push_back(std::move(config));
    }
    return std::make_unique<WritePatchyParticlesStep>(in.name, in.interval(), in.start(), in.end(),
                                                      in.parameters.flag("pbc"), in.members, std::move(writer),
                                                      std::move(patchy), std::move(firstType), std::move(typeNames));
}

}  // namespace

SimulationStepEntry write_patchy_particles_step_entry() {
    return {{"WriteStep", "WritePatchyParticlesStep"}, write_step_parameters(), make};
}

}  // namespace structmd
