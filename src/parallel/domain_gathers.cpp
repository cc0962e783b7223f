// DomainsOverRanks (domains_over_ranks.hpp) as the whole system's view: per-particle arrays gathered
// from the owned slots of every rank into id order, energies summed over them, and what the
// domains refuse.
#include <algorithm>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "parallel/domains_over_ranks.hpp"

namespace structmd {

std::string DomainsOverRanks::refusal(Operation op, PerParticle quantity) const {
    const std::string name = traits(quantity).name;
    switch (op) {
        case Operation::read:
            if (quantity == PerParticle::torques || quantity == PerParticle::magneticMoments) return name;
            if (quantity == PerParticle::pairVirials) return "the virial of pairs";
            return {};
        case Operation::write:
        case Operation::writeSubset:
            if (quantity == PerParticle::externalForces) return "external forces from the host";
            return "setting " + name + (op == Operation::writeSubset ? " of a subset" : "");
        case Operation::readSubset: return name + " of a subset";
        case Operation::view: return "a view of the backend's arrays";
        case Operation::virial: return "the virial (and the pressure)";
        case Operation::externalEnergy: return "an external energy from the host";
        case Operation::setBox: return "changing the box";
        case Operation::setLambda: return "changing lambda";
        case Operation::forceCallback: return "a force callback";
        case Operation::changeParameters: return "changing a parameter";
        case Operation::checkpoint: return "a checkpoint";
        case Operation::termArrays: return {};
        case Operation::hessian: return "the Hessian (HessianMeasure)";
        case Operation::pairForces: return "forces between pairs";
        case Operation::displacedForces: return "forces with a particle displaced";
        case Operation::lambdaDerivative: return "the derivative in lambda";
        case Operation::traversal: return "a transverser over pairs";
    }
    return {};
}

void DomainsOverRanks::gather_owned(const std::vector<double>& local, int k, double* all) {
    const int ranks = comm_->size();
    std::vector<double> counts(static_cast<size_t>(ranks));
    const double mine = static_cast<double>(owned_);
    comm_->all_gather(&mine, counts.data(), std::vector<int64_t>(static_cast<size_t>(ranks), 1));
    std::vector<int64_t> idCounts(static_cast<size_t>(ranks)), valueCounts(static_cast<size_t>(ranks));
    int64_t held = 0;
    for (int r = 0; r < ranks; ++r) {
        idCounts[static_cast<size_t>(r)] = static_cast<int64_t>(counts[static_cast<size_t>(r)]);
        valueCounts[static_cast<size_t>(r)] = k * idCounts[static_cast<size_t>(r)];
        held += idCounts[static_cast<size_t>(r)];
    }
    if (held != total_)
        throw Error(STRUCTMD_ERR_INTERNAL, "the spatial domains hold " + std::to_string(held) + " particles, not " +
                                               std::to_string(total_));
    std::vector<double> myIds(ids_.begin(), ids_.begin() + owned_), allIds(static_cast<size_t>(held));
    comm_->all_gather(myIds.data(), allIds.data(), idCounts);
    std::vector<double> values(static_cast<size_t>(k * held));
    comm_->all_gather(local.data(), values.data(), valueCounts);
    std::vector<char> seen(static_cast<size_t>(total_), 0);
    for (int64_t p = 0; p < held; ++p) {
        const auto id = static_cast<int64_t>(allIds[static_cast<size_t>(p)]);
        if (id < 0 || id >= total_ || seen[static_cast<size_t>(id)])
            throw Error(STRUCTMD_ERR_INTERNAL, "particle id " + std::to_string(id) + " is held by two spatial domains");
        seen[static_cast<size_t>(id)] = 1;
        std::copy(values.begin() + k * p, values.begin() + k * (p + 1), all + k * id);
    }
}

double DomainsOverRanks::sum_owned(const std::vector<double>& values) const {
    double sum = 0.0;
    for (int64_t s = 0; s < owned_; ++s) sum += values[static_cast<size_t>(s)];
    return sum;
}

void DomainsOverRanks::compute(unsigned flags) {
    usable();
    announce(Op::compute, std::string(), flags);
    run_together(*comm_, [&] { local_->compute(flags); });
}

void DomainsOverRanks::read(PerParticle q, double* out) {
    admit(Operation::read, q);
    usable();
    const int k = traits(q).width;
    switch (q) {
        // The view keeps the whole system's copies of what the particles do not change.
        case PerParticle::masses: std::copy(masses_.begin(), masses_.end(), out); return;
        case PerParticle::types: std::copy(types_.begin(), types_.end(), out); return;
        case PerParticle::radii: std::copy(radii_.begin(), radii_.end(), out); return;
        case PerParticle::unwrappedPositions: {
            read(PerParticle::positions, out);
            std::vector<double> images(static_cast<size_t>(3 * total_));
            read(PerParticle::images, images.data());
            for (int64_t c = 0; c < 3 * total_; ++c) out[c] += images[static_cast<size_t>(c)] * box_[c % 3];
            return;
        }
        default: break;
    }
    // Gathered from the owned slots of every rank. Orientations are the identity for all: the domains
    // hold no directions and turn no particle (domain_support.hpp).
    announce(Op::read, std::string(), static_cast<int64_t>(q));
    std::vector<double> local(static_cast<size_t>(k * local_->particle_count()));
    run_together(*comm_, [&] {
        slot_ids();
        local_->read(q, local.data());
    });
    local.resize(static_cast<size_t>(k * owned_));
    gather_owned(local, k, out);
}

double DomainsOverRanks::energy(const std::string& term) {
    usable();
    announce(Op::energy, term);
    double value = 0.0;
    run_together(*comm_, [&] {
        const auto slots = static_cast<size_t>(local_->particle_count());
        const bool kinetic = term == "kinetic" || term == "total";
        const bool potential = term == "potential" || term == "total";
        if (kinetic) {
            std::vector<double> v(3 * slots);
            local_->read(PerParticle::velocities, v.data());
            for (int64_t s = 0; s < owned_; ++s) {
                const double* u = &v[static_cast<size_t>(3 * s)];
                value += 0.5 * masses_[static_cast<size_t>(slot_ids()[static_cast<size_t>(s)])] * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
            }
        }
        if (potential) {
            std::vector<double> e(slots);
            local_->read(PerParticle::energies, e.data());
            value += sum_owned(e);
        }
        if (kinetic || potential) return;
        const std::vector<std::string> names = local_->energy_terms();
        if (std::find(names.begin(), names.end(), term) == names.end())
            throw Error(STRUCTMD_ERR_UNSUPPORTED, "the energy '" + term +
                                                      "' (only kinetic, potential, total and the forceField "
                                                      "entries') is not available " + refusal_reason());
        std::vector<double> e(slots), f(3 * slots), t(3 * slots);
        local_->term_energies_and_forces(term, e.data(), f.data(), t.data());
        value = sum_owned(e);
    });
    comm_->all_sum(&value, 1);
    return value;
}

void DomainsOverRanks::term_energies_and_forces(const std::string& term, double* energies, double* forces,
                                                double* torques) {
    usable();
    announce(Op::termArrays, term);
    const auto slots = static_cast<size_t>(local_->particle_count());
    std::vector<double> e(slots), f(3 * slots), t(3 * slots);
    run_together(*comm_, [&] {
        slot_ids();
        local_->term_energies_and_forces(term, e.data(), f.data(), t.data());
    });
    e.resize(static_cast<size_t>(owned_));
    f.resize(static_cast<size_t>(3 * owned_));
    t.resize(static_cast<size_t>(3 * owned_));
    gather_owned(e, 1, energies);
    gather_owned(f, 3, forces);
    gather_owned(t, 3, torques);
}

}  // namespace structmd
