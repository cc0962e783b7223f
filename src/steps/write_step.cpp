#include "steps/write_step.hpp"

#include <algorithm>
#include <optional>

#include "core/error.hpp"
#include "input/time_step.hpp"
#include "integrators/integrator_spec.hpp"

namespace structmd {

WriteStep::WriteStep(std::string name, int64_t interval, int64_t start, int64_t end, bool wrapped,
                     std::vector<uint8_t> members, std::unique_ptr<TrajectoryWriter> writer,
                     std::vector<std::string> typeNames)
    : SimulationStep(std::move(name), interval, start, end),
      wrapped_(wrapped),
      members_(std::move(members)),
      typeNames_(std::move(typeNames)),
      writer_(std::move(writer)) {}

void WriteStep::run(Simulation& sim) {
    const int64_t n = sim.particle_count();
    positions_.resize(3 * n);
    types_.resize(n);
    radii_.resize(n);
    if (wrapped_)
        sim.get_positions(positions_.data());
    else
        sim.get_unwrapped_positions(positions_.data());
    sim.get_types(types_.data());
    sim.get_radii(radii_.data());
    velocities_.resize(writer_->needs_velocities() ? 3 * n : 0);
    forces_.resize(writer_->needs_forces() ? 3 * n : 0);
    orientations_.resize(writer_->needs_orientations() ? 4 * n : 0);
    moments_.resize(writer_->needs_moments() ? 3 * n : 0);
    if (!velocities_.empty()) sim.get_velocities(velocities_.data());
    if (!forces_.empty()) sim.get_forces(forces_.data());
    if (!orientations_.empty()) sim.get_orientations(orientations_.data());
    if (!moments_.empty()) sim.get_magnetic_moments(moments_.data());

    frame_.step = sim.current_step();
    frame_.time = sim.current_time();
    frame_.box = sim.box();
    frame_.wrapped = wrapped_;
    frame_.typeNames = typeNames_.empty() ? sim.type_names() : typeNames_;
    frame_.ids.clear();
    frame_.positions.clear();
    frame_.types.clear();
    frame_.radii.clear();
    frame_.velocities.clear();
    frame_.forces.clear();
    frame_.orientations.clear();
    frame_.moments.clear();
    for (int64_t i = 0; i < n; ++i) {
        if (!written(i)) continue;
        frame_.ids.push_back(i);
        frame_.positions.insert(frame_.positions.end(), &positions_[3 * i], &positions_[3 * i] + 3);
        frame_.types.push_back(types_[i]);
        frame_.radii.push_back(radii_[i]);
        if (!velocities_.empty())
            frame_.velocities.insert(frame_.velocities.end(), &velocities_[3 * i], &velocities_[3 * i] + 3);
        if (!forces_.empty()) frame_.forces.insert(frame_.forces.end(), &forces_[3 * i], &forces_[3 * i] + 3);
        if (!orientations_.empty())
            frame_.orientations.insert(frame_.orientations.end(), &orientations_[4 * i], &orientations_[4 * i] + 4);
        if (!moments_.empty()) frame_.moments.insert(frame_.moments.end(), &moments_[3 * i], &moments_[3 * i] + 3);
    }
    append(sim, positions_, frame_);
    writer_->write(frame_);
}

void WriteStep::append(Simulation&, const std::vector<double>&, TrajectoryFrame&) {}

namespace {

template <size_t Arity>
void sort_unique(std::vector<std::array<int64_t, Arity>>& rows) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
}

// Chains, residues, masses, charges and the distinct bonds of the input, for PDB and DCD's topology:
// two-particle bonds each pair once, angles and dihedrals as listed.
MoleculeLayout molecule_layout(const StepInput& in) {
    MoleculeLayout layout;
    layout.chain = in.system.chainId;
    layout.residue = in.system.resId;
    layout.mass = in.system.mass;
    layout.charge = in.system.charge;
    for (const BondSpec& bond : in.forceField.bonds) {
        const std::vector<int>& m = bond.members;
        for (size_t k = 0; k + static_cast<size_t>(bond.arity) <= m.size(); k += static_cast<size_t>(bond.arity)) {
            if (bond.arity == 2) layout.bonds.push_back({std::min(m[k], m[k + 1]), std::max(m[k], m[k + 1])});
            if (bond.arity == 3) layout.angles.push_back({m[k], m[k + 1], m[k + 2]});
            if (bond.arity == 4) layout.dihedrals.push_back({m[k], m[k + 1], m[k + 2], m[k + 3]});
        }
    }
    sort_unique(layout.bonds);
    sort_unique(layout.angles);
    sort_unique(layout.dihedrals);
    return layout;
}

// What the frames are apart in time per step (DCD's DELTA): the time step of the first integrator of
// the schedule that moves time forward. A minimisation run first has none, and taking its 0 would
// put every frame of the dynamics after it at time 0 in a reader.
double trajectory_time_step(const input::SystemDescription& system) {
    for (const input::ScheduleRow& row : system.schedule) {
        if (row.steps == 0) continue;
        for (const input::ComponentEntry& entry : system.integrators) {
            if (entry.name != row.integrator) continue;
            const IntegratorComponent* component = integrator_registry().find({entry.cls, entry.subclass});
            if (component && component->minimiser) continue;
            if (const std::optional<double> timeStep = input::time_step_of(entry, system)) return *timeStep;
        }
    }
    return input::first_time_step(system).value_or(0.0);  // 0: DCD's unknown
}

std::string known_formats() {
    std::string list;
    for (const std::string& format : trajectory_formats()) list += (list.empty() ? "" : ", ") + format;
    return list;
}

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    std::unique_ptr<TrajectoryWriter> writer = trajectory_writer_of(in);
    return std::make_unique<WriteStep>(in.name, in.interval(), in.start(), in.end(), in.parameters.flag("pbc"),
                                       in.members, std::move(writer));
}

}  // namespace

std::unique_ptr<TrajectoryWriter> trajectory_writer_of(const StepInput& in) {
    const std::string format = in.parameters.text("outputFormat");
    TrajectoryOptions options;
    options.path = in.parameters.text("outputFilePath") + "." + format;
    options.owner = in.path;
    options.append = in.parameters.flag("append");
    options.interval = in.interval();
    options.timeStep = trajectory_time_step(in.system);
    if (format == "pdb" || format == "dcd") options.molecules = molecule_layout(in);

    std::unique_ptr<TrajectoryWriter> writer = make_trajectory_writer(format, std::move(options));
    if (!writer)
        throw input_error(in.parameters.path("outputFormat"),
                          "unknown output format '" + format + "'; known: " + known_formats());
    if (writer->needs_moments() && in.system.magnetizations.empty())
        throw input_error(in.parameters.path("outputFormat"),
                          "format '" + format + "' writes magnetic moments: the state needs a 'magnetization' column");
    return writer;
}

std::vector<StepParameter> write_step_parameters() {
    return step_parameters({{"outputFilePath", StepValue::text, nullptr, Must::be_finite, "",
                             "the file written is <outputFilePath>.<outputFormat>"},
                            {"outputFormat", StepValue::text, nullptr, Must::be_finite, "",
                             "a trajectory format (trajectory_formats()), which is also the extension"},
                            {"pbc", StepValue::flag, true, Must::be_finite, "",
                             "true: positions wrapped into the box; false: unwrapped"},
                            {"append", StepValue::flag, false, Must::be_finite, "",
                             "extend an existing file instead of replacing it"}});
}

SimulationStepEntry write_step_entry() {
    SimulationStepEntry entry{{"WriteStep", "WriteStep"}, write_step_parameters(), make};
    entry.underDomains = true;  // writes the positions (and velocities) gathered from every domain
    return entry;
}

}  // namespace structmd
