#pragma once
// An integrator advances the particles by one step; it asks the engine for forces at the positions
// it needs them, and the engine evaluates only what is stale.
#include "simulation/particles.hpp"

namespace structmd {

class ForceSource {
public:
    virtual ~ForceSource() = default;
    // Makes the force array current for the present positions.
    virtual void update_forces() = 0;
    // Tells the engine the integrator moved the particles to the next step's positions, `elapsed`
    // time later (terms active at that step and fields at that time then apply).
    virtual void positions_moved(double elapsed) = 0;
};

template <class B, class R>
class Integrator {
public:
    explicit Integrator(double timeStep) : timeStep_(timeStep) {}
    virtual ~Integrator() = default;
    double time_step() const { return timeStep_; }
    virtual void step(Particles<B, R>& particles, ForceSource& forces) = 0;

private:
    double timeStep_;
};

}  // namespace structmd
