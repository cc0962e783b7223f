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
#include "simulation/simulation.hpp"
#include "steps/measure_file.hpp"

namespace structmd {

class ReplicaExchange final : public Simulation {
public:
    // replicas: this rank's, in increasing temperature index (k = rank, rank + K, ...). Collective.
    ReplicaExchange(std::vector<std::unique_ptr<Simulation>> replicas, std::shared_ptr<const Communicator> comm,
                    ReplicaExchangeSpec spec);

    // What the exchanges did so far, for structmd_get_info: per pair (k, k+1), attempts and acceptances.
    const ReplicaExchangeSpec& spec() const { return spec_; }
    const std::vector<int64_t>& attempts() const { return attempts_; }
    const std::vector<int64_t>& accepted() const { return accepted_; }

    void advance(int64_t n) override;

    int64_t particle_count() const override { return front().particle_count(); }
    int64_t massive_count() const override { return front().massive_count(); }
    int64_t current_step() const override { return front().current_step(); }
    double current_time() const override { return front().current_time(); }
    int64_t final_step() const override { return front().final_step(); }
    double boltzmann() const override { return front().boltzmann(); }
    std::array<double, 3> box() const override { return front().box(); }
    double volume() const override { return front().volume(); }
    void request_stop(const std::string& by) override { front().request_stop(by); }
    const std::string& stopped_by() const override { return front().stopped_by(); }
    void set_step_firing(StepFiring* firing) override { front().set_step_firing(firing); }
    void compute(unsigned flags) override { front().compute(flags); }
    void get_positions(double* xyz) override { front().get_positions(xyz); }
    void get_images(int32_t* images) override { front().get_images(images); }
    void get_unwrapped_positions(double* xyz) override { front().get_unwrapped_positions(xyz); }
    void get_velocities(double* v) override { front().get_velocities(v); }
    void get_forces(double* f) override { front().get_forces(f); }
    void get_particle_energies(double* e) override { front().get_particle_energies(e); }
    void get_masses(double* m) override { front().get_masses(m); }
    void get_types(int32_t* types) override { front().get_types(types); }
    void get_radii(double* r) override { front().get_radii(r); }
    void get_orientations(double* q) override { front().get_orientations(q); }
    void set_orientations(const double* q) override { front().set_orientations(q); }
    void get_torques(double* t) override { front().get_torques(t); }
    void get_magnetic_moments(double* m) override { front().get_magnetic_moments(m); }
    bool has_magnetization() const override { return front().has_magnetization(); }
    const std::vector<std::string>& type_names() const override { return front().type_names(); }
    double energy(const std::string& term) override { return front().energy(term); }
    std::vector<std::string> energy_terms() const override { return front().energy_terms(); }
    void term_energies_and_forces(const std::string& term, double* e, double* f, double* t) override {
        front().term_energies_and_forces(term, e, f, t);
    }
    std::array<double, 9> virial() override { return front().virial(); }
    void get_pair_virials(double* w) override { front().get_pair_virials(w); }
    void hessian_column(int64_t id, double* blocks) override { front().hessian_column(id, blocks); }
    void pair_forces_on(int64_t id, double* f) override { front().pair_forces_on(id, f); }
    void forces_with_displaced(int64_t id, const double d[3], double* f) override {
        front().forces_with_displaced(id, d, f);
    }
    void set_positions(const double* xyz) override { front().set_positions(xyz); }
    void set_velocities(const double* v) override { front().set_velocities(v); }
    void set_box(const double lengths[3]) override;
    void set_external_forces(const double* f) override { front().set_external_forces(f); }
    double lambda() const override { return front().lambda(); }
    void set_lambda(double lambda) override { front().set_lambda(lambda); }
    double lambda_derivative() override { return front().lambda_derivative(); }
    void get_positions_of(const int64_t* ids, int64_t m, double* xyz) override { front().get_positions_of(ids, m, xyz); }
    void get_velocities_of(const int64_t* ids, int64_t m, double* v) override { front().get_velocities_of(ids, m, v); }
    void get_forces_of(const int64_t* ids, int64_t m, double* f) override { front().get_forces_of(ids, m, f); }
    void set_positions_of(const int64_t* ids, int64_t m, const double* xyz) override {
        front().set_positions_of(ids, m, xyz);
    }
    void set_velocities_of(const int64_t* ids, int64_t m, const double* v) override {
        front().set_velocities_of(ids, m, v);
    }
    void set_external_forces_of(const int64_t* ids, int64_t m, const double* f) override {
        front().set_external_forces_of(ids, m, f);
    }
    void set_external_energy(double e) override { front().set_external_energy(e); }
    double external_energy() const override { return front().external_energy(); }
    void set_force_callback(HostForceCallback callback) override;
    void set_device_force_callback(DeviceForceCallback callback) override;
    ArrayView view(const std::string& quantity) override { return front().view(quantity); }
    void change_parameters(const RuntimeSpec& spec, const ForceFieldComponents& components) override;
    void save_checkpoint(const std::string& path) override;
    void load_checkpoint(const std::string& path) override;
    Counters counters() override { return front().counters(); }
    std::string backend_name() const override { return front().backend_name(); }
    std::string precision_name() const override { return front().precision_name(); }
    std::string device_name() const override { return front().device_name(); }
    int threads() const override { return front().threads(); }
    std::optional<double> overdamped_kT() const override { return front().overdamped_kT(); }

private:
    Simulation& front() const { return *replicas_.front(); }
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
