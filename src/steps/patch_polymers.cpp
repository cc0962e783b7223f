#include "steps/patch_polymers.hpp"

#include <algorithm>
#include <cstring>

#include "core/error.hpp"

namespace structmd {

namespace {

// UAMMD-structured's event types (Events.dat); it leaves out the negative-direction ones (1, 3),
// which the positive ones of the partner imply.
enum EventType : int32_t { polymerization = 0, depolymerization = 2, toSurface = 4, toBulk = 5 };

constexpr const char* kDistribution = "PolymerDistribution.dat";
constexpr const char* kSurfaceDistribution = "SurfacePolymerDistribution.dat";
constexpr const char* kSurfaceFraction = "FractionMonomersInSurface.dat";
constexpr const char* kTransitions = "TransitionMatrix.dat";
constexpr const char* kEvents = "Events.dat";

}  // namespace

PatchPolymers::PatchPolymers(std::string name, int64_t interval, int64_t start, int64_t end, Files files, int maxLen,
                             std::string bondedEntry, std::shared_ptr<const PatchyConfig> bonded, int endType,
                             std::shared_ptr<const PatchyConfig> surface, double surfaceEnergyThreshold,
                             Monomers monomers)
    : SimulationStep(name, interval, start, end),
      maxLen_(maxLen),
      bondedEntry_(std::move(bondedEntry)),
      bonded_(std::move(bonded)),
      endType_(endType),
      surface_(std::move(surface)),
      threshold_(surfaceEnergyThreshold),
      monomers_(std::move(monomers)),
      distribution_("simulationStep." + name, files.prefix + kDistribution, ""),
      transitions_("simulationStep." + name, files.prefix + kTransitions, "") {
    const std::string owner = "simulationStep." + name;
    if (surface_) {
        surfaceDistribution_.emplace(owner, files.prefix + kSurfaceDistribution, "");
        surfaceFraction_.emplace(owner, files.prefix + kSurfaceFraction, "");
    }
    if (files.writeEvents) events_.emplace(owner, files.prefix + kEvents, "");
    const int64_t largest = monomers_.ids.empty() ? -1 : monomers_.ids.back();
    localOf_.assign(static_cast<size_t>(largest + 1), -1);
    for (size_t m = 0; m < monomers_.ids.size(); ++m) localOf_[monomers_.ids[m]] = static_cast<int>(m);
}

std::vector<int> PatchPolymers::start_partners(Simulation& sim) const {
    const std::vector<int> bonds = sim.probes().patch_bonds(bondedEntry_);
    std::vector<int> partners(monomers_.ids.size(), -1);
    for (size_t m = 0; m < partners.size(); ++m) {
        const int patch = bonds[monomers_.startPatch[m]];
        if (patch < 0) continue;
        const int parent = bonded_->parent[patch];
        if (parent >= static_cast<int>(localOf_.size()) || localOf_[parent] < 0) continue;
        if (bonded_->type[patch] != endType_)
            throw Error(STRUCTMD_ERR_STATE, "simulationStep." + name() + ": the start patch of particle " +
                                                std::to_string(monomers_.ids[m]) + " is bonded to a patch of type '" +
                                                bonded_->typeNames[bonded_->type[patch]] +
                                                "' of particle " + std::to_string(parent) +
                                                "; PatchPolymers counts bonds from start to end patches only");
        partners[m] = localOf_[parent];
    }
    return partners;
}

// A monomer is on the surface when its linker patch's energy (the Linker term, 0 for a type the term
// does not list) is below the threshold; its height is its parent's position in the box plus the
// turned offset, as the term takes it.
std::vector<bool> PatchPolymers::on_surface(Simulation& sim) const {
    const size_t n = monomers_.ids.size();
    std::vector<double> positions(3 * n), orientations(4 * static_cast<size_t>(sim.particle_count()));
    sim.get_positions_of(monomers_.ids.data(), static_cast<int64_t>(n), positions.data());
    sim.get_orientations(orientations.data());
    std::vector<bool> on(n, false);
    for (size_t m = 0; m < n; ++m) {
        const int patch = monomers_.linkerPatch[m];
        const int type = surface_->type[patch];
        if (surface_->linker.empty() || !surface_->linkerListed[type]) {
            on[m] = 0.0 < threshold_;
            continue;
        }
        const double* q = &orientations[4 * static_cast<size_t>(monomers_.ids[m])];
        const Vec3<double> turned =
            patch_math::apply(patch_math::frame_of(Real4<double>{q[0], q[1], q[2], q[3]}), surface_->offset[patch]);
        double forceZ = 0.0;
        on[m] = LinkerPatch::evaluate(positions[3 * m + 2] + turned.z, surface_->linker[type], forceZ) < threshold_;
    }
    return on;
}

// One packed record of 20 bytes in the host's byte order: step (uint64), id (int32), type (int32),
// info (int32), as UAMMD-structured writes its event struct.
void PatchPolymers::write_event(int64_t step, int monomer, int type, int64_t info) {
    unsigned char record[20];
    const uint64_t s = static_cast<uint64_t>(step);
    const int32_t fields[3] = {static_cast<int32_t>(monomers_.ids[monomer]), type, static_cast<int32_t>(info)};
    std::memcpy(record, &s, 8);
    std::memcpy(record + 8, fields, 12);
    std::fwrite(record, 1, sizeof(record), events_->stream());
}

void PatchPolymers::run(Simulation& sim) {
    const int64_t step = sim.current_step();
    const int n = static_cast<int>(monomers_.ids.size());
    if (!tracker_) {
        tracker_.emplace(n, maxLen_, step);
        partners_.assign(n, -1);
        surfaceNow_.assign(n, false);
    }
    const std::vector<int> partners = start_partners(sim);
    // Bonds broken first, then bonds made: between the two every patch of a new bond is free, so each
    // new bond joins the end of a chain to the start of one (or closes a ring).
    for (int m = 0; m < n; ++m)
        if (partners_[m] >= 0 && partners[m] != partners_[m]) {
            if (events_) write_event(step, m, depolymerization, monomers_.ids[partners_[m]]);
            tracker_->depolymerize(step, m, partners_[m]);
        }
    for (int m = 0; m < n; ++m)
        if (partners[m] >= 0 && partners[m] != partners_[m]) {
            if (events_) write_event(step, m, polymerization, monomers_.ids[partners[m]]);
            tracker_->polymerize(step, m, partners[m]);
        }
    partners_ = partners;
    if (surface_) {
        const std::vector<bool> surfaceNow = on_surface(sim);
        for (int m = 0; m < n; ++m)
            if (surfaceNow[m] != surfaceNow_[m]) {
                if (events_) write_event(step, m, surfaceNow[m] ? toSurface : toBulk, 0);
                tracker_->move_to_surface(step, m, surfaceNow[m]);
            }
        surfaceNow_ = surfaceNow;
    }
    if (events_) events_->flush();
    write_outputs(step);
}

void PatchPolymers::write_outputs(int64_t step) {
    const auto write_distribution = [&](MeasureFile& file, bool onSurface) {
        std::FILE* out = file.stream();
        std::fprintf(out, "# %lld\n", static_cast<long long>(step));
        const std::vector<int64_t> counts = tracker_->distribution(onSurface);
        for (size_t k = 0; k < counts.size(); ++k) std::fprintf(out, "%zu %lld\n", k, static_cast<long long>(counts[k]));
        file.flush();
    };
    write_distribution(distribution_, false);
    if (surface_) {
        write_distribution(*surfaceDistribution_, true);
        std::fprintf(surfaceFraction_->stream(), "%lld %.17g\n", static_cast<long long>(step),
                     tracker_->surface_fraction());
        surfaceFraction_->flush();
    }
    std::FILE* out = transitions_.stream();
    std::fprintf(out, "# %lld\n", static_cast<long long>(step));
    for (const auto& [states, count] : tracker_->transitions())
        std::fprintf(out, "%s %s %llu\n", states.first.c_str(), states.second.c_str(),
                     static_cast<unsigned long long>(count));
    transitions_.flush();
}

namespace {

// The only entry of its kind among the patchy entries, or null; a second one is an input error.
const ExternalSpec* only_entry(const StepInput& in, const std::string& subclass) {
    const ExternalSpec* found = nullptr;
    for (const ExternalSpec& external : in.forceField.externals)
        if (external.key.cls == "PatchyParticles" && external.key.subclass == subclass) {
            if (found)
                throw input_error(in.path, "PatchPolymers takes one [\"PatchyParticles\",\"" + subclass +
                                               "\"] entry; the force field has '" + found->name + "' and '" +
                                               external.name + "'");
            found = &external;
        }
    return found;
}

int type_named(const StepInput& in, const PatchyConfig& config, const std::string& parameter,
               const std::string& entry) {
    const std::string name = in.parameters.text(parameter);
    const auto at = std::find(config.typeNames.begin(), config.typeNames.end(), name);
    if (at == config.typeNames.end())
        throw input_error(in.parameters.path(parameter), "no patch type '" + name + "' in forceField entry '" + entry + "'");
    return static_cast<int>(at - config.typeNames.begin());
}

// By monomer, its one patch of each wanted type in `config` (-1 for a type not wanted); an input
// error at the step's path when a monomer has another patch, or not exactly one of a wanted type.
std::vector<std::vector<int>> patches_of(const StepInput& in, const std::vector<int64_t>& ids,
                                         const PatchyConfig& config, const std::vector<int>& wanted,
                                         const std::string& entry) {
    std::vector<int> local(static_cast<size_t>(in.system.numParticles()), -1);
    for (size_t m = 0; m < ids.size(); ++m) local[ids[m]] = static_cast<int>(m);
    std::vector<std::vector<int>> found(wanted.size(), std::vector<int>(ids.size(), -1));
    for (size_t a = 0; a < config.parent.size(); ++a) {
        const int m = local[config.parent[a]];
        if (m < 0) continue;
        const auto which = std::find(wanted.begin(), wanted.end(), config.type[a]) - wanted.begin();
        if (which == static_cast<std::ptrdiff_t>(wanted.size()))
            throw input_error(in.path, "patch " + std::to_string(a) + " of forceField entry '" + entry + "' is of type '" +
                                           config.typeNames[config.type[a]] + "', which PatchPolymers does not take");
        if (found[which][m] >= 0)
            throw input_error(in.path, "particle " + std::to_string(config.parent[a]) + " has more than one patch of type '" +
                                           config.typeNames[config.type[a]] + "' in forceField entry '" + entry + "'");
        found[which][m] = static_cast<int>(a);
    }
    for (size_t w = 0; w < wanted.size(); ++w)
        for (size_t m = 0; m < ids.size(); ++m)
            if (found[w][m] < 0)
                throw input_error(in.path, "particle " + std::to_string(ids[m]) + " has no patch of type '" +
                                               config.typeNames[wanted[w]] + "' in forceField entry '" + entry + "'");
    return found;
}

// Bonds of a start patch to a start patch (or an end to an end) would not make chains.
void require_start_end_pairs(const StepInput& in, const PatchyConfig& config, int startType, int endType,
                             const std::string& entry) {
    const int t = config.ntypes();
    for (int type : {startType, endType}) {
        const size_t same = static_cast<size_t>(type * t + type);
        const bool listed = (!config.cosine.empty() && config.cosineListed[same]) ||
                            (!config.cosrap.empty() && config.cosrapListed[same]);
        if (listed)
            throw input_error(in.path, "forceField entry '" + entry + "' lets patches of type '" +
                                           config.typeNames[type] + "' bond to each other; PatchPolymers needs every "
                                           "bond between a start and an end patch");
    }
}

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    const ExternalSpec* bondedEntry = only_entry(in, "DynamicallyBondedPatchyParticles");
    if (!bondedEntry)
        throw input_error(in.path, "PatchPolymers needs a [\"PatchyParticles\",\"DynamicallyBondedPatchyParticles\"] "
                                   "forceField entry");
    auto bonded = std::static_pointer_cast<const PatchyConfig>(bondedEntry->config);
    const int startType = type_named(in, *bonded, "startType", bondedEntry->name);
    const int endType = type_named(in, *bonded, "endType", bondedEntry->name);
    if (startType == endType)
        throw input_error(in.parameters.path("endType"), "the end patches' type must differ from the start patches'");
    require_start_end_pairs(in, *bonded, startType, endType, bondedEntry->name);

    PatchPolymers::Monomers monomers;
    monomers.ids = in.member_ids();
    monomers.startPatch = patches_of(in, monomers.ids, *bonded, {startType, endType}, bondedEntry->name)[0];

    std::shared_ptr<const PatchyConfig> surface;
    if (const ExternalSpec* surfaceEntry = only_entry(in, "PatchyParticles")) {
        surface = std::static_pointer_cast<const PatchyConfig>(surfaceEntry->config);
        if (surface->hasPairs)
            throw input_error(in.path, "forceField entry '" + surfaceEntry->name + "' (the surface for PatchPolymers) "
                                       "must hold [\"SurfacePatches\",...] terms only");
        const int linkerType = type_named(in, *surface, "linkerType", surfaceEntry->name);
        monomers.linkerPatch = patches_of(in, monomers.ids, *surface, {linkerType}, surfaceEntry->name)[0];
    }
    PatchPolymers::Files files{in.parameters.text("outputFilePath"), in.parameters.flag("writeEvents")};
    in.log.info(in.path + ": " + std::to_string(monomers.ids.size()) + " monomers" +
                (surface ? ", with a surface" : ", no surface") +
                "; bonds and surface events are detected at each firing (intervalStep " +
                std::to_string(in.interval()) + ")");
    return std::make_unique<PatchPolymers>(in.name, in.interval(), in.start(), in.end(), std::move(files),
                                           static_cast<int>(in.parameters.integer("maxLen")), bondedEntry->name,
                                           std::move(bonded), endType, std::move(surface),
                                           in.parameters.number("surfaceEnergyThreshold"), std::move(monomers));
}

}  // namespace

SimulationStepEntry patch_polymers_entry() {
    return {{"TopologicalMeasures", "PatchPolymers"},
            step_parameters({
                {"outputFilePath", StepValue::text, nullptr, Must::be_finite, "",
                 "the prefix of the files written: <outputFilePath>PolymerDistribution.dat, ..."},
                {"startType", StepValue::text, "S", Must::be_finite, "",
                 "the type of the start patches (in the DynamicallyBondedPatchyParticles entry)"},
                {"endType", StepValue::text, "E", Must::be_finite, "", "the type of the end patches"},
                {"linkerType", StepValue::text, "L", Must::be_finite, "",
                 "the type of the linker patches (in the PatchyParticles entry of the surface)"},
                {"surfaceEnergyThreshold", StepValue::number, 0.0, Must::be_finite, "energy",
                 "a monomer is on the surface while its linker patch's energy is below it"},
                {"writeEvents", StepValue::flag, false, Must::be_finite, "", "whether to write Events.dat"},
                {"maxLen", StepValue::integer, int64_t{25}, Must::be_non_negative, "",
                 "longest chain (bonds) whose state keys give the positions"},
                {"bufferSize", StepValue::integer, nullptr, Must::be_positive, "",
                 "read and checked only: the events are found at each firing, nothing is buffered"},
            }),
            make};
}

}  // namespace structmd
