#include "parallel/replica_exchange.hpp"

#include <Random123/philox.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"

namespace structmd {

namespace {

// The stream of the exchanges' uniform numbers: purpose 5, beside the particles' noise purposes
// (integrators/thermal_noise.hpp) in the same (seed, stream, step) numbering, and the pair's index.
constexpr uint64_t kExchangePurpose = 5;

// A uniform number in (0, 1) for the attempt of pair k at this step.
double exchange_uniform(uint64_t seed, int k, int64_t step) {
    typedef r123::Philox4x32 Generator;
    const uint64_t stream = (kExchangePurpose << 48) ^ static_cast<uint64_t>(k);
    const Generator::key_type key = {{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)}};
    const Generator::ctr_type ctr = {{static_cast<uint32_t>(step), static_cast<uint32_t>(static_cast<uint64_t>(step) >> 32),
                                      static_cast<uint32_t>(stream), static_cast<uint32_t>(stream >> 32)}};
    const Generator::ctr_type bits = Generator()(ctr, key);
    return (static_cast<double>(bits.v[0]) + 0.5) * 2.3283064365386963e-10;  // 2^-32
}

}  // namespace

ReplicaExchange::ReplicaExchange(std::vector<std::unique_ptr<Simulation>> replicas,
                                 std::shared_ptr<const Communicator> comm, ReplicaExchangeSpec spec)
    : replicas_(std::move(replicas)), comm_(std::move(comm)), spec_(std::move(spec)),
      attempts_(spec_.temperatures.size() - 1, 0), accepted_(spec_.temperatures.size() - 1, 0) {}

void ReplicaExchange::advance(int64_t n) {
    if (n < 0) throw Error(STRUCTMD_ERR_ARGUMENT, "nsteps: expected a count >= 0, got " + std::to_string(n));
    const int64_t end = current_step() + n;
    while (current_step() < end) {
        const int64_t step = current_step();
        const int64_t next = std::min(end, (step / spec_.interval + 1) * spec_.interval);
        run_together(*comm_, [&] {
            for (auto& replica : replicas_) {
                replica->advance(next - step);
                if (!replica->stopped_by().empty())
                    throw Error(STRUCTMD_ERR_UNSUPPORTED, "simulationStep." + replica->stopped_by() +
                                                              ": a flow-control step under parallel tempering, whose "
                                                              "replicas step together");
            }
        });
        const int64_t now = current_step();
        if (now % spec_.interval == 0 && now >= spec_.start && now <= spec_.end) exchange();
    }
}

void ReplicaExchange::exchange() {
    const int replicas = static_cast<int>(spec_.temperatures.size());
    const int64_t step = current_step();
    // Each replica's potential energy, from its rank (the others add zeros, exactly).
    std::vector<double> energy(static_cast<size_t>(replicas), 0.0);
    run_together(*comm_, [&] {
        for (int k = comm_->rank(); k < replicas; k += comm_->size()) energy[k] = replica(k).energy("potential");
    });
    comm_->all_sum(energy.data(), replicas);

    std::vector<int> outcome(static_cast<size_t>(replicas - 1), -1);
    const double kB = boltzmann();
    for (int k = static_cast<int>((step / spec_.interval) % 2); k + 1 < replicas; k += 2) {
        const double beta = 1.0 / (kB * spec_.temperatures[k]), betaNext = 1.0 / (kB * spec_.temperatures[k + 1]);
        const double exponent = (beta - betaNext) * (energy[k] - energy[k + 1]);
        const bool accept = exponent >= 0.0 || exchange_uniform(spec_.seed, k, step) < std::exp(exponent);
        ++attempts_[k];
        outcome[k] = accept ? 1 : 0;
        if (!accept) continue;
        ++accepted_[k];
        swap(k, k + 1);
    }

    if (comm_->rank() != 0) return;
    if (!file_) {
        std::string header = "#step";
        for (int k = 0; k + 1 < replicas; ++k) header += " exchanged" + std::to_string(k) + "-" + std::to_string(k + 1);
        for (int k = 0; k + 1 < replicas; ++k) header += " acceptance" + std::to_string(k) + "-" + std::to_string(k + 1);
        file_.emplace("simulationStep." + spec_.name, spec_.outputPath, std::move(header));
    }
    std::FILE* out = file_->stream();
    std::fprintf(out, "%lld", static_cast<long long>(step));
    for (int result : outcome) std::fprintf(out, result < 0 ? " -" : " %d", result);
    for (size_t k = 0; k < attempts_.size(); ++k)
        std::fprintf(out, " %.10g", attempts_[k] > 0 ? static_cast<double>(accepted_[k]) / attempts_[k] : 0.0);
    std::fputc('\n', out);
    file_->flush();
}

std::vector<double> ReplicaExchange::configuration(int from, int to) const {
    Simulation& source = replica(from);
    const auto n = static_cast<size_t>(source.particle_count());
    std::vector<double> state(6 * n);
    source.get_positions(state.data());
    source.get_velocities(state.data() + 3 * n);
    // Inertial dynamics: the velocities take the temperature they go to; overdamped has none.
    if (!source.overdamped_kT()) {
        const double scale = std::sqrt(spec_.temperatures[to] / spec_.temperatures[from]);
        for (size_t i = 3 * n; i < 6 * n; ++i) state[i] *= scale;
    }
    return state;
}

void ReplicaExchange::place(int k, const std::vector<double>& state) {
    Simulation& target = replica(k);
    const size_t n = state.size() / 6;
    target.write(PerParticle::positions, state.data());
    target.write(PerParticle::velocities, state.data() + 3 * n);
}

void ReplicaExchange::swap(int a, int b) {
    const int me = comm_->rank();
    if (owner(a) == me && owner(b) == me) {
        const std::vector<double> fromA = configuration(a, b), fromB = configuration(b, a);
        place(b, fromA);
        place(a, fromB);
        return;
    }
    const int mine = owner(a) == me ? a : owner(b) == me ? b : -1;
    if (mine < 0) return;
    const int other = mine == a ? b : a;
    const std::vector<double> outgoing = configuration(mine, other);
    std::vector<double> incoming(outgoing.size());
    comm_->send_receive(outgoing.data(), incoming.data(), static_cast<int64_t>(outgoing.size()), owner(other));
    place(mine, incoming);
}

void ReplicaExchange::set_box(const double lengths[3]) {
    for (auto& replica : replicas_) replica->set_box(lengths);
}

std::string ReplicaExchange::refusal(Operation op, PerParticle) const {
    switch (op) {
        case Operation::forceCallback: return "a force callback";
        case Operation::changeParameters: return "changing a parameter";
        case Operation::checkpoint: return "a checkpoint";
        default: return {};
    }
}

}  // namespace structmd
