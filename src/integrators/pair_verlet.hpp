#pragma once
// What ["DPD","Verlet"] and ["SPH","Verlet"] share: velocity Verlet (velocity_verlet.hpp) driven by
// the force field's forces plus pair forces the integrator owns, over a Verlet list of its own: they
// read the velocities, which force-field terms never see, so they cannot be terms of the force
// field. As UAMMD's VerletNVE with UAMMD-structured's DPD and SPH interactors does, the pair forces at
// the new positions are computed with the half-step velocities; they are kept, beside the force
// field's, for the first half kick of the next step unless the positions changed in between (another
// integrator, the host), in which case they are computed again with the velocities then. They are
// the integrator's state: a checkpoint holds them, so a restart continues the same trajectory.
#include <cstdint>
#include <vector>

#include "integrators/integrator.hpp"
#include "integrators/thermal_noise.hpp"
#include "integrators/velocity_verlet.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

// What both read besides timeStep, temperature and group.
struct PairVerletInputs : IntegratorInputs {
    static std::vector<Parameter> parameters() { return {with_default(boolean("resetVelocities"), 1.0)}; }
    // One fluid for every particle, as UAMMD-structured, which refuses more than one batch.
    static constexpr bool oneFluid = true;
};

template <class B, class R>
class PairVerlet : public Integrator<B, R> {
public:
    PairVerlet(const B& backend, const IntegratorScope& scope, const ParameterValues& v, double cutoff)
        : Integrator<B, R>(scope),
          backend_(backend),
          list_(backend, cutoff, kListRadiusFactor, PairCondition::all, PairFilterInputs{}, nullptr, 1, nullptr),
          resetVelocities_(v["resetVelocities"] != 0.0) {}

    void begin(Particles<B, R>& p, ForceSource&) override {
        const IntegratorScope& s = this->scope();
        if (resetVelocities_)
            backend_.for_each(p.count, DrawThermalVelocities<R>{p.vel.data(), s.group, p.noise, p.now(), R(s.kT)});
        pairForcesAt_ = -1;  // the velocities may have changed: computed afresh at the first step
        restored_.clear();
    }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        const R dt = R(s.timeStep);
        versionNow_ = &p.version;
        forces.update_forces();
        if (static_cast<int64_t>(restored_.size()) == 3 * p.count)
            take_restored(p);
        else if (pairForcesAt_ != p.version)
            update_pair_forces(p);
        restored_.clear();
        backend_.for_each(p.count, VerletKickDrift<R>{s.group, p.pos.data(), p.image.data(), p.vel.data(),
                                                      p.force.data(), p.box, dt, p.fault_slot(1), p.drift,
                                                      pairForce_.data()});
        forces.positions_moved(s.timeStep, true);
        forces.update_forces();
        update_pair_forces(p);
        backend_.for_each(p.count, ClosingHalfKick<R>{s.group, p.vel.data(), p.force.data(), dt, p.fault_slot(),
                                                      pairForce_.data()});
        // The list's capacity grows from what its builds needed (a host round trip, so now and then);
        // until then a particle with more neighbours is served by scanning its cells.
        if (++stepsSinceAdapt_ >= kStepsBetweenAdapts) {
            list_.adapt();
            stepsSinceAdapt_ = 0;
        }
    }

    // The pair forces (x, y, z by particle) while they belong to the present positions; none otherwise.
    // A download: the engine asks at every step call (for its roll back) and at checkpoints.
    std::vector<double> state() const override {
        if (!versionNow_ || pairForcesAt_ != *versionNow_) return {};
        std::vector<Real4<R>> forces(pairForce_.size());
        backend_.download(pairForce_, forces.data(), forces.size());
        std::vector<double> flat;
        flat.reserve(3 * forces.size());
        for (const Real4<R>& f : forces) flat.insert(flat.end(), {double(f.x), double(f.y), double(f.z)});
        return flat;
    }
    // Taken at the next step, for the positions and velocities restored with them; a state of another
    // size (of no particles, or edited) is ignored and the forces computed afresh.
    void restore(const std::vector<double>& state) override { restored_ = state; }

protected:
    // Writes (not adds) each particle's pair force into `out`, by particle; zero outside the group.
    virtual void compute_pair_forces(Particles<B, R>& p, const NeighbourView<R>& neighbours, Real4<R>* out) = 0;

    const B& backend_;

private:
    void update_pair_forces(Particles<B, R>& p) {
        if (static_cast<int64_t>(pairForce_.size()) != p.count) backend_.resize(pairForce_, p.count);
        list_.update(p.pos, p.count, p.box, p.version);
        compute_pair_forces(p, list_.view(), pairForce_.data());
        pairForcesAt_ = p.version;
    }

    void take_restored(Particles<B, R>& p) {
        std::vector<Real4<R>> forces(p.count);
        for (int64_t i = 0; i < p.count; ++i)
            forces[i] = Real4<R>{R(restored_[3 * i]), R(restored_[3 * i + 1]), R(restored_[3 * i + 2]), R(0)};
        backend_.upload(pairForce_, forces.data(), forces.size());
        pairForcesAt_ = p.version;
    }

    static constexpr double kListRadiusFactor = 1.25;  // list radius / cutoff: a skin of a quarter cutoff
    static constexpr int kStepsBetweenAdapts = 500;

    VerletList<B, R> list_;
    typename B::template Buffer<Real4<R>> pairForce_;
    int64_t pairForcesAt_ = -1;  // the positions version pairForce_ belongs to
    const int64_t* versionNow_ = nullptr;  // the positions version of the particles it steps
    std::vector<double> restored_;  // pair forces a restore gave, for the next step
    int stepsSinceAdapt_ = 0;
    bool resetVelocities_;
};

}  // namespace structmd
