#include "parallel/batches_over_ranks.hpp"

#include <algorithm>
#include <cstring>

#include "core/error.hpp"
#include "steps/simulation_step.hpp"

namespace structmd {

BatchesOverRanks::BatchesOverRanks(std::unique_ptr<Simulation> local, std::shared_ptr<const Communicator> comm,
                                   std::vector<int64_t> counts, std::vector<int> batches)
    : StepsOnRankZero(std::move(comm)), local_(std::move(local)), counts_(std::move(counts)), batches_(std::move(batches)) {
    for (int r = 0; r < comm_->rank(); ++r) firstId_ += counts_[static_cast<size_t>(r)];
    for (int64_t c : counts_) total_ += c;
    double massive = static_cast<double>(local_->massive_count());
    comm_->all_sum(&massive, 1);
    massive_ = static_cast<int64_t>(massive);
    local_->set_step_firing(this);
}

BatchesOverRanks::~BatchesOverRanks() { local_->set_step_firing(nullptr); }

void BatchesOverRanks::set_step_firing(StepFiring*) {
    throw Error(STRUCTMD_ERR_INTERNAL, "the steps of batches over ranks are fired by the view itself");
}

void BatchesOverRanks::unsupported(const std::string& what) const {
    throw Error(STRUCTMD_ERR_UNSUPPORTED, what + " is not available while batches are spread over MPI ranks");
}

void BatchesOverRanks::advance(int64_t n) {
    run_together(*comm_, [&] { local_->advance(n); });
}

// ---- gathers and sums ----

void BatchesOverRanks::gather(const std::vector<double>& mine, double* all, int k) {
    std::vector<int64_t> counts(counts_);
    for (int64_t& c : counts) c *= k;
    comm_->all_gather(mine.data(), all, counts);
}

template <class Get>
void BatchesOverRanks::gather_per_particle(Op op, double* all, int k, Get&& get) {
    announce(op);
    std::vector<double> mine(static_cast<size_t>(k * local_count()));
    run_together(*comm_, [&] { get(mine.data()); });
    gather(mine, all, k);
}

void BatchesOverRanks::compute(unsigned flags) {
    announce(Op::compute, std::string(), flags);
    run_together(*comm_, [&] { local_->compute(flags); });
}

void BatchesOverRanks::get_positions(double* xyz) {
    gather_per_particle(Op::positions, xyz, 3, [&](double* mine) { local_->get_positions(mine); });
}
void BatchesOverRanks::get_unwrapped_positions(double* xyz) {
    gather_per_particle(Op::unwrappedPositions, xyz, 3, [&](double* mine) { local_->get_unwrapped_positions(mine); });
}
void BatchesOverRanks::get_velocities(double* v) {
    gather_per_particle(Op::velocities, v, 3, [&](double* mine) { local_->get_velocities(mine); });
}
void BatchesOverRanks::get_forces(double* f) {
    gather_per_particle(Op::forces, f, 3, [&](double* mine) { local_->get_forces(mine); });
}
void BatchesOverRanks::get_particle_energies(double* e) {
    gather_per_particle(Op::particleEnergies, e, 1, [&](double* mine) { local_->get_particle_energies(mine); });
}
void BatchesOverRanks::get_masses(double* m) {
    gather_per_particle(Op::masses, m, 1, [&](double* mine) { local_->get_masses(mine); });
}
void BatchesOverRanks::get_radii(double* r) {
    gather_per_particle(Op::radii, r, 1, [&](double* mine) { local_->get_radii(mine); });
}
void BatchesOverRanks::get_orientations(double* q) {
    gather_per_particle(Op::orientations, q, 4, [&](double* mine) { local_->get_orientations(mine); });
}
void BatchesOverRanks::get_torques(double* t) {
    gather_per_particle(Op::torques, t, 3, [&](double* mine) { local_->get_torques(mine); });
}
void BatchesOverRanks::get_magnetic_moments(double* m) {
    gather_per_particle(Op::magneticMoments, m, 3, [&](double* mine) { local_->get_magnetic_moments(mine); });
}
void BatchesOverRanks::get_pair_virials(double* w) {
    gather_per_particle(Op::pairVirials, w, 9, [&](double* mine) { local_->get_pair_virials(mine); });
}

void BatchesOverRanks::get_images(int32_t* images) {
    announce(Op::images);
    std::vector<int32_t> mine(static_cast<size_t>(3 * local_count()));
    run_together(*comm_, [&] { local_->get_images(mine.data()); });
    std::vector<int64_t> counts(counts_);
    for (int64_t& c : counts) c *= 3;
    comm_->all_gather(mine.data(), images, counts);
}

void BatchesOverRanks::get_types(int32_t* types) {
    announce(Op::types);
    std::vector<int32_t> mine(static_cast<size_t>(local_count()));
    run_together(*comm_, [&] { local_->get_types(mine.data()); });
    comm_->all_gather(mine.data(), types, counts_);
}

double BatchesOverRanks::energy(const std::string& term) {
    announce(Op::energy, term);
    // term@batch:K is the rank's that holds batch K; the others add nothing.
    double value = 0.0;
    const size_t at = term.find("@batch:");
    bool mine = true;
    if (at != std::string::npos) {
        try {
            size_t used = 0;
            const std::string text = term.substr(at + 7);
            const int batch = std::stoi(text, &used);
            if (used == text.size()) {
                const bool anywhere = comm_->all_max(std::binary_search(batches_.begin(), batches_.end(), batch)) != 0;
                mine = !anywhere || std::binary_search(batches_.begin(), batches_.end(), batch);
            }
        } catch (const std::logic_error&) {
            // Not a number: the engine names the term as malformed, on every rank alike.
        }
    }
    run_together(*comm_, [&] {
        if (mine) value = local_->energy(term);
    });
    comm_->all_sum(&value, 1);
    return value;
}

void BatchesOverRanks::term_energies_and_forces(const std::string& term, double* energies, double* forces,
                                                double* torques) {
    announce(Op::termArrays, term);
    const auto n = static_cast<size_t>(local_count());
    std::vector<double> e(n), f(3 * n), t(3 * n);
    run_together(*comm_, [&] { local_->term_energies_and_forces(term, e.data(), f.data(), t.data()); });
    gather(e, energies, 1);
    gather(f, forces, 3);
    gather(t, torques, 3);
}

std::array<double, 9> BatchesOverRanks::virial() {
    announce(Op::virial);
    std::array<double, 9> w{};
    run_together(*comm_, [&] { w = local_->virial(); });
    comm_->all_sum(w.data(), 9);
    return w;
}

void BatchesOverRanks::set_lambda(double lambda) {
    announce(Op::setLambda, std::string(), 0, lambda);
    run_together(*comm_, [&] { local_->set_lambda(lambda); });
}

double BatchesOverRanks::lambda_derivative() {
    announce(Op::lambdaDerivative);
    double value = 0.0;
    run_together(*comm_, [&] { value = local_->lambda_derivative(); });
    comm_->all_sum(&value, 1);
    return value;
}

// ---- the host's setters: every rank passes the whole system's arrays ----

void BatchesOverRanks::set_positions(const double* xyz) {
    if (driving()) unsupported("setting positions from a simulation step");
    run_together(*comm_, [&] { local_->set_positions(slice(xyz, 3)); });
}
void BatchesOverRanks::set_velocities(const double* v) {
    if (driving()) unsupported("setting velocities from a simulation step");
    run_together(*comm_, [&] { local_->set_velocities(slice(v, 3)); });
}
void BatchesOverRanks::set_orientations(const double* q) {
    if (driving()) unsupported("setting orientations from a simulation step");
    run_together(*comm_, [&] { local_->set_orientations(slice(q, 4)); });
}
void BatchesOverRanks::set_box(const double lengths[3]) {
    if (driving()) unsupported("setting the box from a simulation step");
    run_together(*comm_, [&] { local_->set_box(lengths); });
}
void BatchesOverRanks::set_external_forces(const double* f) {
    if (driving()) unsupported("setting external forces from a simulation step");
    run_together(*comm_, [&] { local_->set_external_forces(f ? slice(f, 3) : nullptr); });
}
void BatchesOverRanks::set_external_energy(double energy) {
    // The host's field belongs to no batch: rank 0 carries it, so that sums over ranks count it once.
    run_together(*comm_, [&] { local_->set_external_energy(comm_->rank() == 0 ? energy : 0.0); });
    externalEnergy_ = energy;
}

// Subsets: picked from the whole system's arrays; each rank sets the ids it holds.
namespace {
void pick(const std::vector<double>& all, const int64_t* ids, int64_t m, double* out) {
    for (int64_t k = 0; k < m; ++k)
        for (int d = 0; d < 3; ++d) out[3 * k + d] = all[static_cast<size_t>(3 * ids[k] + d)];
}
}  // namespace

void BatchesOverRanks::get_positions_of(const int64_t* ids, int64_t m, double* xyz) {
    std::vector<double> all(static_cast<size_t>(3 * total_));
    get_positions(all.data());
    pick(all, ids, m, xyz);
}
void BatchesOverRanks::get_velocities_of(const int64_t* ids, int64_t m, double* v) {
    std::vector<double> all(static_cast<size_t>(3 * total_));
    get_velocities(all.data());
    pick(all, ids, m, v);
}
void BatchesOverRanks::get_forces_of(const int64_t* ids, int64_t m, double* f) {
    std::vector<double> all(static_cast<size_t>(3 * total_));
    get_forces(all.data());
    pick(all, ids, m, f);
}

namespace {
// The entries of ids[0..m) in [first, first + count), shifted to the share's ids, and their values.
void held(const int64_t* ids, int64_t m, const double* values, int64_t first, int64_t count,
          std::vector<int64_t>& localIds, std::vector<double>& localValues) {
    for (int64_t k = 0; k < m; ++k) {
        if (ids[k] < first || ids[k] >= first + count) continue;
        localIds.push_back(ids[k] - first);
        localValues.insert(localValues.end(), values + 3 * k, values + 3 * k + 3);
    }
}
}  // namespace

void BatchesOverRanks::set_positions_of(const int64_t* ids, int64_t m, const double* xyz) {
    if (driving()) unsupported("setting positions from a simulation step");
    std::vector<int64_t> localIds;
    std::vector<double> values;
    held(ids, m, xyz, firstId_, local_count(), localIds, values);
    run_together(*comm_, [&] { local_->set_positions_of(localIds.data(), static_cast<int64_t>(localIds.size()), values.data()); });
}
void BatchesOverRanks::set_velocities_of(const int64_t* ids, int64_t m, const double* v) {
    if (driving()) unsupported("setting velocities from a simulation step");
    std::vector<int64_t> localIds;
    std::vector<double> values;
    held(ids, m, v, firstId_, local_count(), localIds, values);
    run_together(*comm_, [&] { local_->set_velocities_of(localIds.data(), static_cast<int64_t>(localIds.size()), values.data()); });
}
void BatchesOverRanks::set_external_forces_of(const int64_t* ids, int64_t m, const double* f) {
    if (driving()) unsupported("setting external forces from a simulation step");
    std::vector<int64_t> localIds;
    std::vector<double> values;
    held(ids, m, f, firstId_, local_count(), localIds, values);
    run_together(*comm_, [&] {
        local_->set_external_forces_of(localIds.data(), static_cast<int64_t>(localIds.size()), values.data());
    });
}

// ---- what needs the whole system in one engine ----

void BatchesOverRanks::hessian_column(int64_t, double*) { unsupported("the Hessian (HessianMeasure)"); }
void BatchesOverRanks::pair_forces_on(int64_t, double*) { unsupported("forces between pairs"); }
void BatchesOverRanks::forces_with_displaced(int64_t, const double*, double*) {
    unsupported("forces with a particle displaced");
}
void BatchesOverRanks::set_force_callback(HostForceCallback) { unsupported("a force callback"); }
void BatchesOverRanks::set_device_force_callback(DeviceForceCallback) { unsupported("a device force callback"); }
Simulation::ArrayView BatchesOverRanks::view(const std::string&) { unsupported("a view of the backend's arrays"); }
void BatchesOverRanks::change_parameters(const RuntimeSpec&, const ForceFieldComponents&) {
    unsupported("changing a parameter");
}
void BatchesOverRanks::save_checkpoint(const std::string&) { unsupported("a checkpoint"); }
void BatchesOverRanks::load_checkpoint(const std::string&) { unsupported("a checkpoint"); }

}  // namespace structmd
