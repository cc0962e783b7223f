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
#include "simulation/simulation.hpp"

namespace structmd {

class BatchesOverRanks final : public StepsOnRankZero {
public:
    // `local`: this rank's engine, loaded from its share; counts: every rank's particle count;
    // batches: the batchId values of this rank's share. Collective.
    BatchesOverRanks(std::unique_ptr<Simulation> local, std::shared_ptr<const Communicator> comm,
                     std::vector<int64_t> counts, std::vector<int> batches);
    ~BatchesOverRanks() override;

    int64_t particle_count() const override { return total_; }
    int64_t massive_count() const override { return massive_; }
    int64_t current_step() const override { return local_->current_step(); }
    double current_time() const override { return local_->current_time(); }
    int64_t final_step() const override { return local_->final_step(); }
    double boltzmann() const override { return local_->boltzmann(); }
    std::array<double, 3> box() const override { return local_->box(); }
    double volume() const override { return local_->volume(); }

    void advance(int64_t n) override;
    void request_stop(const std::string& by) override { local_->request_stop(by); }
    const std::string& stopped_by() const override { return local_->stopped_by(); }
    void set_step_firing(StepFiring*) override;
    void compute(unsigned flags) override;

    void get_positions(double* xyz) override;
    void get_images(int32_t* images) override;
    void get_unwrapped_positions(double* xyz) override;
    void get_velocities(double* v) override;
    void get_forces(double* f) override;
    void get_particle_energies(double* e) override;
    void get_masses(double* m) override;
    void get_types(int32_t* types) override;
    void get_radii(double* r) override;
    void get_orientations(double* q) override;
    void set_orientations(const double* q) override;
    void get_torques(double* t) override;
    void get_magnetic_moments(double* m) override;
    bool has_magnetization() const override { return local_->has_magnetization(); }
    const std::vector<std::string>& type_names() const override { return local_->type_names(); }

    double energy(const std::string& term) override;
    std::vector<std::string> energy_terms() const override { return local_->energy_terms(); }
    void term_energies_and_forces(const std::string& term, double* energies, double* forces, double* torques) override;
    std::array<double, 9> virial() override;
    void get_pair_virials(double* w) override;

    void hessian_column(int64_t id, double* blocks) override;
    void pair_forces_on(int64_t id, double* f) override;
    void forces_with_displaced(int64_t id, const double displacement[3], double* f) override;

    void set_positions(const double* xyz) override;
    void set_velocities(const double* v) override;
    void set_box(const double lengths[3]) override;
    void set_external_forces(const double* f) override;

    double lambda() const override { return local_->lambda(); }
    void set_lambda(double lambda) override;
    double lambda_derivative() override;

    void get_positions_of(const int64_t* ids, int64_t m, double* xyz) override;
    void get_velocities_of(const int64_t* ids, int64_t m, double* v) override;
    void get_forces_of(const int64_t* ids, int64_t m, double* f) override;
    void set_positions_of(const int64_t* ids, int64_t m, const double* xyz) override;
    void set_velocities_of(const int64_t* ids, int64_t m, const double* v) override;
    void set_external_forces_of(const int64_t* ids, int64_t m, const double* f) override;

    void set_external_energy(double energy) override;
    double external_energy() const override { return externalEnergy_; }

    void set_force_callback(HostForceCallback callback) override;
    void set_device_force_callback(DeviceForceCallback callback) override;
    ArrayView view(const std::string& quantity) override;
    void change_parameters(const RuntimeSpec& spec, const ForceFieldComponents& components) override;
    void save_checkpoint(const std::string& path) override;
    void load_checkpoint(const std::string& path) override;

    Counters counters() override { return local_->counters(); }  // this rank's
    std::string backend_name() const override { return local_->backend_name(); }
    std::string precision_name() const override { return local_->precision_name(); }
    std::string device_name() const override { return local_->device_name(); }
    int threads() const override { return local_->threads(); }
    std::optional<double> overdamped_kT() const override { return local_->overdamped_kT(); }

private:
    // k values per particle from every share into `all`, in id order.
    void gather(const std::vector<double>& mine, double* all, int k);
    template <class Get>
    void gather_per_particle(Op op, double* all, int k, Get&& get);
    // The rank's slice of a whole-system array of k values per particle.
    const double* slice(const double* all, int k) const { return all + k * firstId_; }
    int64_t local_count() const { return counts_[static_cast<size_t>(comm_->rank())]; }
    [[noreturn]] void unsupported(const std::string& what) const;

    std::unique_ptr<Simulation> local_;
    std::vector<int64_t> counts_;
    std::vector<int> batches_;
    int64_t firstId_ = 0;
    int64_t total_ = 0;
    int64_t massive_ = 0;
    double externalEnergy_ = 0.0;
};

}  // namespace structmd
