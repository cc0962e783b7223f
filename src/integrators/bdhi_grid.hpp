#pragma once
// What the Brownian-hydrodynamics integrators that spread the particles on a grid share (force
// coupling, positively split Ewald, quasi-2D, DPStokes): overdamped motion, and a grid made for the
// box the integrator starts with, prepared again before every step.
#include <string>
#include <vector>

#include "integrators/bdhi_kernels.hpp"
#include "integrators/brownian.hpp"
#include "integrators/integrator.hpp"

namespace structmd {

// The inputs of a grid method for spheres of one given radius (force coupling, quasi-2D).
struct GridBdhiInputs : IntegratorInputs {
    static constexpr bool oneFluid = true;
    static std::vector<Parameter> parameters() {
        return {number("viscosity", "mass/(length time)", Must::be_positive),
                number("hydrodynamicRadius", "length", Must::be_positive),
                with_default(number("tolerance", "1", Must::be_positive), 1e-3)};
    }
    static constexpr bool overdamped = true;
    static void validate(const ParameterValues& v, const std::string& path) { validate_grid_tolerance(v, path); }
};

template <class B, class R>
class GridBdhi : public Integrator<B, R> {
public:
    GridBdhi(const B& backend, const IntegratorScope& scope) : Integrator<B, R>(scope), backend_(backend) {}

    bool overdamped() const override { return true; }

    // Overdamped particles have no velocity of their own: the kinetic energy reads 0.
    void begin(Particles<B, R>& p, ForceSource&) override {
        backend_.for_each(p.count, StopParticles<R>{p.vel.data(), this->scope().group});
        prepare(p);
    }

protected:
    // Makes the grid for the present box on the first call, refuses a box it cannot follow on later
    // ones, and sizes the buffers for the present particles.
    virtual void prepare(const Particles<B, R>& p) = 0;

    // Moves the group by a displacement the grid made whole (dt M F and the noise, flat).
    void move_by(Particles<B, R>& p, ForceSource& forces, const R* displacement) {
        const IntegratorScope& s = this->scope();
        backend_.for_each(p.count, BdhiMove<R>{p.pos.data(), p.image.data(), p.force.data(), nullptr, nullptr,
                                               displacement, s.group, p.box, R(0), R(0), p.fault_slot(1), p.drift});
        forces.positions_moved(s.timeStep, true);
    }

    const B& backend_;
};

}  // namespace structmd
