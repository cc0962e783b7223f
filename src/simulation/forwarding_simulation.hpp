#pragma once
// A view that shows another simulation, its inner() (an engine, or a replica): every call goes on to
// it unless the view overrides the call or refuses it. The views over MPI ranks (parallel/) derive
// from it and override only what they change. What a view cannot do is declared by refusal(), one
// table per view, checked before the calls below go on; nothing refuses by default.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "simulation/simulation.hpp"
#include "simulation/simulation_probes.hpp"

namespace structmd {

class ForwardingSimulation : public Simulation, public SimulationProbes {
public:
    int64_t particle_count() const override { return inner().particle_count(); }
    int64_t massive_count() const override { return inner().massive_count(); }
    ScheduleClock clock() const override { return inner().clock(); }
    double boltzmann() const override { return inner().boltzmann(); }
    std::array<double, 3> box() const override { return inner().box(); }
    const std::vector<std::string>& type_names() const override { return inner().type_names(); }
    std::optional<double> overdamped_kT() const override { return inner().overdamped_kT(); }
    EngineDescription description() const override { return inner().description(); }
    Counters counters() override { return inner().counters(); }

    void advance(int64_t n) override { inner().advance(n); }
    void request_stop(const std::string& by) override { inner().request_stop(by); }
    const std::string& stopped_by() const override { return inner().stopped_by(); }
    void compute(unsigned flags) override { inner().compute(flags); }

    void read(PerParticle q, double* out) override {
        admit(Operation::read, q);
        inner().read(q, out);
    }
    void write(PerParticle q, const double* in) override {
        admit(Operation::write, q);
        inner().write(q, in);
    }
    void read_of(PerParticle q, const int64_t* ids, int64_t m, double* out) override {
        admit(Operation::readSubset, q);
        inner().read_of(q, ids, m, out);
    }
    void write_of(PerParticle q, const int64_t* ids, int64_t m, const double* in) override {
        admit(Operation::writeSubset, q);
        inner().write_of(q, ids, m, in);
    }
    ArrayView view(const std::string& quantity) override {
        admit(Operation::view);
        return inner().view(quantity);
    }

    double energy(const std::string& term) override { return inner().energy(term); }
    std::vector<std::string> energy_terms() const override { return inner().energy_terms(); }
    std::array<double, 9> virial() override {
        admit(Operation::virial);
        return inner().virial();
    }
    void set_external_energy(double energy) override {
        admit(Operation::externalEnergy);
        inner().set_external_energy(energy);
    }
    void set_box(const double lengths[3]) override {
        admit(Operation::setBox);
        inner().set_box(lengths);
    }
    double lambda() const override { return inner().lambda(); }
    void set_lambda(double lambda) override {
        admit(Operation::setLambda);
        inner().set_lambda(lambda);
    }
    void set_force_callback(ForceCallback callback) override {
        admit(Operation::forceCallback);
        inner().set_force_callback(std::move(callback));
    }
    void change_parameters(const RuntimeSpec& spec, const ForceFieldComponents& components) override {
        admit(Operation::changeParameters);
        inner().change_parameters(spec, components);
    }
    void save_checkpoint(const std::string& path) override {
        admit(Operation::checkpoint);
        inner().save_checkpoint(path);
    }
    void load_checkpoint(const std::string& path) override {
        admit(Operation::checkpoint);
        inner().load_checkpoint(path);
    }

    SimulationProbes& probes() final { return *this; }
    void term_energies_and_forces(const std::string& term, double* energies, double* forces,
                                  double* torques) override {
        admit(Operation::termArrays);
        inner().probes().term_energies_and_forces(term, energies, forces, torques);
    }
    void hessian_column(int64_t id, double* blocks) override {
        admit(Operation::hessian);
        inner().probes().hessian_column(id, blocks);
    }
    void pair_forces_on(int64_t id, double* f) override {
        admit(Operation::pairForces);
        inner().probes().pair_forces_on(id, f);
    }
    void forces_with_displaced(int64_t id, const double displacement[3], double* f) override {
        admit(Operation::displacedForces);
        inner().probes().forces_with_displaced(id, displacement, f);
    }
    double lambda_derivative() override {
        admit(Operation::lambdaDerivative);
        return inner().probes().lambda_derivative();
    }
    void expression_sum(const ExpressionTransverserSpec& spec, double* perParticle) override {
        admit(Operation::traversal);
        inner().probes().expression_sum(spec, perParticle);
    }
    void traverse(const TransverserCall& call, double* perParticle) override {
        admit(Operation::traversal);
        inner().probes().traverse(call, perParticle);
    }
    TransverserOutput traverse_on_backend(const TransverserCall& call) override {
        admit(Operation::traversal);
        return inner().probes().traverse_on_backend(call);
    }
    std::vector<int> patch_bonds(const std::string& entry) override {
        admit(Operation::termArrays);
        return inner().probes().patch_bonds(entry);
    }
    bool has_magnetization() const override { return inner().probes().has_magnetization(); }

protected:
    // The calls a view may refuse.
    enum class Operation {
        read, write, readSubset, writeSubset, view, virial, externalEnergy, setBox, setLambda, forceCallback,
        changeParameters, checkpoint, termArrays, hessian, pairForces, displacedForces, lambdaDerivative,
        traversal,
    };
    // The simulation the calls go on to.
    virtual Simulation& inner() const = 0;
    // What this view cannot do, in words ("changing the box"), for `op` on `quantity` (the
    // per-particle calls); empty when it can. The view's refusal names its own reason.
    virtual std::string refusal(Operation /*op*/, PerParticle /*quantity*/) const { return {}; }
    // Throws ERR_UNSUPPORTED, naming what refusal() says and the view's reason, when it refuses.
    void admit(Operation op, PerParticle quantity = PerParticle::positions) const;
    // The view's reason, for refusals: "under domain decomposition".
    virtual std::string refusal_reason() const = 0;
};

}  // namespace structmd
