#pragma once
// Parallel tempering (["ReplicaExchange","ParallelTempering"]): one replica of the input per
// temperature, replica k on rank k mod K of the handle's communicator (several per rank where there
// are more replicas than ranks, all of them in one process without MPI). Every intervalStep steps
// the replicas' potential energies are gathered and neighbouring temperatures (k, k+1), the even
// pairs at one attempt and the odd ones at the next, exchange configurations by the Metropolis rule:
// accepted with probability min(1, exp((1/kT_k - 1/kT_k+1) (U_k - U_k+1))), the uniform number keyed
// by the system's seed, the step and the pair, so that any split over ranks makes the same
// exchanges. Each replica keeps its temperature; positions move with the configuration, velocities
// too, scaled by sqrt(T_new / T_old) under inertial dynamics.
//
// The handle shows the rank's first replica (rank 0: the first temperature) to the host, its calls
// on the others' configurations aside; stepping is collective over the ranks.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "parallel/communicator.hpp"
#include "parallel/replica_documents.hpp"
#include "simulation/forwarding_simulation.hpp"
#include "steps/measure_file.hpp"

namespace structmd {

class ReplicaExchange final : public ForwardingSimulation {
public:
    // replicas: this rank's, in increasing temperature index (k = rank, rank + K, ...). Collective.
    ReplicaExchange(std::vector<std::unique_ptr<Simulation>> replicas, std::shared_ptr<const Communicator> comm,
                    ReplicaExchangeSpec spec);

    // What the exchanges did so far, for structmd_get_info: per pair (k, k+1), attempts and acceptances.
    const ReplicaExchangeSpec& spec() const { return spec_; }
    const std::vector<int64_t>& attempts() const { return attempts_; }
    const std::vector<int64_t>& accepted() const { return accepted_; }

    void advance(int64_t n) override;
    void set_box(const double lengths[3]) override;

private:
    Simulation& inner() const override { return *replicas_.front(); }
    std::string refusal(Operation op, PerParticle quantity) const override;
    std::string refusal_reason() const override { return "under parallel tempering"; }
    int owner(int k) const { return k % comm_->size(); }
    Simulation& replica(int k) const { return *replicas_[static_cast<size_t>(k / comm_->size())]; }
    void exchange();
    // Moves the configurations of replicas a and b (a < b) past each other.
    void swap(int a, int b);
    // A replica's positions and velocities (6n), the velocities scaled to the temperature it goes to.
    std::vector<double> configuration(int from, int to) const;
    void place(int k, const std::vector<double>& configuration);

    std::vector<std::unique_ptr<Simulation>> replicas_;
    std::shared_ptr<const Communicator> comm_;
    ReplicaExchangeSpec spec_;
    std::vector<int64_t> attempts_, accepted_;
    std::optional<MeasureFile> file_;  // rank 0's
};

}  // namespace structmd
