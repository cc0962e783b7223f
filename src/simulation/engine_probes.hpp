#pragma once
// Engine's probes (SimulationProbes): what simulation steps ask beyond the state, computed into
// buffers made when first asked for (ProbeBuffers).
#include <string>
#include <vector>

#include "forcefield/patchy_particles.hpp"
#include "simulation/engine.hpp"

namespace structmd {

template <class B, class R, class PairR>
void Engine<B, R, PairR>::term_energies_and_forces(const std::string& term, double* energies, double* forces,
                                                   double* torques) {
    const int index = forceField_.find(term);
    if (index < 0) throw Error(STRUCTMD_ERR_ARGUMENT, "no forceField entry named '" + term + "'");
    backend_.activate();
    refresh_ghosts();
    const Real4<R> zero{R(0), R(0), R(0), R(0)};
    backend_.resize(probed_.energies, p_.count);
    backend_.fill(probed_.energies, R(0));
    backend_.resize(probed_.forces, p_.count);
    backend_.fill(probed_.forces, zero);
    backend_.resize(probed_.torques, p_.count);
    backend_.fill(probed_.torques, zero);
    ForceOutputs<R> out;
    out.energy = probed_.energies.data();
    out.force = probed_.forces.data();
    out.torque = probed_.torques.data();
    forceField_.compute_one(index, p_, out);
    ForceCache<B, R>::count(out, evaluations_);
    const std::vector<R> values = io_.download(probed_.energies);
    std::copy(values.begin(), values.end(), energies);
    io_.download_vectors(probed_.forces, forces);
    io_.download_vectors(probed_.torques, torques);
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::hessian_column(int64_t id, double* blocks) {
    if (!context_.hessian) throw Error(STRUCTMD_ERR_STATE, "no step of this input asks for second derivatives");
    backend_.activate();
    backend_.resize(probed_.hessian, p_.count);
    backend_.fill(probed_.hessian, zero_tensor<R>());
    forceField_.add_hessian(p_, static_cast<int>(id), probed_.hessian.data());
    const std::vector<Tensor3<R>> values = io_.download(probed_.hessian);
    for (int64_t j = 0; j < p_.count; ++j) {
        const Tensor3<R>& t = values[j];
        const R block[9] = {t.xx, t.xy, t.xz, t.yx, t.yy, t.yz, t.zx, t.zy, t.zz};
        std::copy(block, block + 9, blocks + 9 * j);
    }
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::pair_forces_on(int64_t id, double* f) {
    if (!probed_.pairForces) throw Error(STRUCTMD_ERR_STATE, "no step of this input asks for pair forces");
    backend_.activate();
    backend_.resize(probed_.forces, p_.count);
    backend_.fill(probed_.forces, Real4<R>{R(0), R(0), R(0), R(0)});
    forceField_.add_pair_forces(p_, static_cast<int>(id), probed_.forces.data());
    io_.download_vectors(probed_.forces, f);
}

// The particle is moved in the positions array and back; the version moves on each time, so
// neither a cached force nor a list refresh of the moved positions outlives the call.
template <class B, class R, class PairR>
void Engine<B, R, PairR>::forces_with_displaced(int64_t id, const double displacement[3], double* f) {
    backend_.activate();
    const Real4<R> original = io_.position_of(id);
    const Vec3<R> moved = p_.box.wrap(Vec3<R>{R(original.x + displacement[0]), R(original.y + displacement[1]),
                                              R(original.z + displacement[2])});
    io_.place_position(id, Real4<R>{moved.x, moved.y, moved.z, original.w});
    ++p_.version;
    backend_.resize(probed_.forces, p_.count);
    backend_.fill(probed_.forces, Real4<R>{R(0), R(0), R(0), R(0)});
    ForceOutputs<R> out;
    out.force = probed_.forces.data();
    forceField_.prepare(p_);
    forceField_.compute_all(p_, out);
    ForceCache<B, R>::count(out, evaluations_);
    io_.place_position(id, original);
    ++p_.version;
    io_.download_vectors(probed_.forces, f);
}

template <class B, class R, class PairR>
double Engine<B, R, PairR>::lambda_derivative() {
    if (!forceField_.couples_to_lambda()) return 0.0;
    backend_.activate();
    backend_.resize(probed_.lambdaDerivatives, p_.count);
    backend_.fill(probed_.lambdaDerivatives, R(0));
    forceField_.add_lambda_derivative(p_, probed_.lambdaDerivatives.data());
    return backend_.reduce(p_.count, SumEnergy<R>{probed_.lambdaDerivatives.data()}, 0.0);
}

template <class B, class R, class PairR>
std::vector<int> Engine<B, R, PairR>::patch_bonds(const std::string& entry) {
    const int index = forceField_.find(entry);
    const auto* patchy = index < 0 ? nullptr : dynamic_cast<const PatchyInteraction<B, R>*>(&forceField_.interactor(index));
    if (!patchy || !patchy->dynamic())
        throw Error(STRUCTMD_ERR_ARGUMENT, "no [\"PatchyParticles\",\"DynamicallyBondedPatchyParticles\"] forceField entry "
                                           "named '" + entry + "'");
    backend_.activate();
    return io_.download(patchy->bonds_buffer());
}

}  // namespace structmd
