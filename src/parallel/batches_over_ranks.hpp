#pragma once
// The simulation of a handle whose batches are spread over the ranks of an MPI communicator: each
// rank's engine holds its share (batch_split.hpp), and this view shows the whole system, in the
// one-rank id order, to the host and to the simulation steps.
//
// Every call on it is collective: all ranks of the communicator make the same calls in the same
// order (as the launcher and an SPMD host program do). Per-particle arrays are gathered from the
// shares, so they are the one-rank arrays bit for bit; sums over the whole system (energies, the
// virial) are the shares' sums added over the ranks, equal to the one-rank values to rounding. An
// energy of one batch (term@batch:K) is its rank's.
//
// Simulation steps fire on rank 0 only (steps_on_rank_zero.hpp).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "parallel/communicator.hpp"
#include "parallel/steps_on_rank_zero.hpp"
#include "simulation/local_engine.hpp"

namespace structmd {

class BatchesOverRanks final : public StepsOnRankZero {
public:
    // `local`: this rank's engine, loaded from its share; counts: every rank's particle count;
    // batches: the batchId values of this rank's share. Collective.
    BatchesOverRanks(std::unique_ptr<LocalEngine> local, std::shared_ptr<const Communicator> comm,
                     std::vector<int64_t> counts, std::vector<int> batches);
    ~BatchesOverRanks() override;

    int64_t particle_count() const override { return total_; }
    int64_t massive_count() const override { return massive_; }

    void advance(int64_t n) override;
    void compute(unsigned flags) override;
    void read(PerParticle q, double* out) override;
    void write(PerParticle q, const double* in) override;
    void read_of(PerParticle q, const int64_t* ids, int64_t m, double* out) override;
    void write_of(PerParticle q, const int64_t* ids, int64_t m, const double* in) override;

    double energy(const std::string& term) override;
    std::array<double, 9> virial() override;
    void set_external_energy(double energy) override;
    void set_box(const double lengths[3]) override;
    void set_lambda(double lambda) override;

    void term_energies_and_forces(const std::string& term, double* energies, double* forces, double* torques) override;
    double lambda_derivative() override;

private:
    Simulation& inner() const override { return *local_; }
    std::string refusal(Operation op, PerParticle quantity) const override;
    std::string refusal_reason() const override { return "while batches are spread over MPI ranks"; }
    // k values per particle from every share into `all`, in id order.
    void gather(const std::vector<double>& mine, double* all, int k);
    // The rank's slice of a whole-system array of k values per particle.
    const double* slice(const double* all, int k) const { return all + k * firstId_; }
    int64_t local_count() const { return counts_[static_cast<size_t>(comm_->rank())]; }

    std::unique_ptr<LocalEngine> local_;
    std::vector<int64_t> counts_;
    std::vector<int> batches_;
    int64_t firstId_ = 0;
    int64_t total_ = 0;
    int64_t massive_ = 0;
};

}  // namespace structmd
