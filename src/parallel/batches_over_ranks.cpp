#include "parallel/batches_over_ranks.hpp"

#include <algorithm>
#include <cstring>

#include "core/error.hpp"
#include "steps/simulation_step.hpp"

namespace structmd {

BatchesOverRanks::BatchesOverRanks(std::unique_ptr<LocalEngine> local, std::shared_ptr<const Communicator> comm,
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

std::string BatchesOverRanks::refusal(Operation op, PerParticle quantity) const {
    // A simulation step fires on rank 0 alone, while the others serve its gathers: it cannot hand
    // every rank the whole system's arrays a setter needs.
    if (driving()) {
        if (op == Operation::write || op == Operation::writeSubset)
            return std::string("setting ") + traits(quantity).name + " from a simulation step";
        if (op == Operation::setBox) return "setting the box from a simulation step";
    }
    switch (op) {
        case Operation::hessian: return "the Hessian (HessianMeasure)";
        case Operation::pairForces: return "forces between pairs";
        case Operation::displacedForces: return "forces with a particle displaced";
        case Operation::forceCallback: return "a force callback";
        case Operation::view: return "a view of the backend's arrays";
        case Operation::changeParameters: return "changing a parameter";
        case Operation::checkpoint: return "a checkpoint";
        case Operation::traversal: return "a transverser over pairs";
        default: return {};
    }
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

void BatchesOverRanks::compute(unsigned flags) {
    announce(Op::compute, std::string(), flags);
    run_together(*comm_, [&] { local_->compute(flags); });
}

void BatchesOverRanks::read(PerParticle q, double* out) {
    admit(Operation::read, q);
    announce(Op::read, std::string(), static_cast<int64_t>(q));
    const int k = traits(q).width;
    std::vector<double> mine(static_cast<size_t>(k * local_count()));
    run_together(*comm_, [&] { local_->read(q, mine.data()); });
    gather(mine, out, k);
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

void BatchesOverRanks::write(PerParticle q, const double* in) {
    admit(Operation::write, q);
    run_together(*comm_, [&] { local_->write(q, in ? slice(in, traits(q).width) : nullptr); });
}
void BatchesOverRanks::set_box(const double lengths[3]) {
    admit(Operation::setBox);
    run_together(*comm_, [&] { local_->set_box(lengths); });
}
void BatchesOverRanks::set_external_energy(double energy) {
    // The host's field belongs to no batch: rank 0 carries it, so that sums over ranks count it once.
    run_together(*comm_, [&] { local_->set_external_energy(comm_->rank() == 0 ? energy : 0.0); });
}

// Subsets: picked from the whole system's arrays; each rank sets the ids it holds.
void BatchesOverRanks::read_of(PerParticle q, const int64_t* ids, int64_t m, double* out) {
    std::vector<double> all(static_cast<size_t>(3 * total_));
    read(q, all.data());
    for (int64_t k = 0; k < m; ++k)
        for (int d = 0; d < 3; ++d) out[3 * k + d] = all[static_cast<size_t>(3 * ids[k] + d)];
}

void BatchesOverRanks::write_of(PerParticle q, const int64_t* ids, int64_t m, const double* in) {
    admit(Operation::writeSubset, q);
    // The entries of ids in this rank's share, shifted to the share's ids, and their values.
    std::vector<int64_t> localIds;
    std::vector<double> values;
    for (int64_t k = 0; k < m; ++k) {
        if (ids[k] < firstId_ || ids[k] >= firstId_ + local_count()) continue;
        localIds.push_back(ids[k] - firstId_);
        values.insert(values.end(), in + 3 * k, in + 3 * k + 3);
    }
    run_together(*comm_, [&] { local_->write_of(q, localIds.data(), static_cast<int64_t>(localIds.size()), values.data()); });
}

}  // namespace structmd
