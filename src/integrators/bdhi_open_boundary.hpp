#pragma once
// Brownian dynamics with hydrodynamic interactions in an unbounded fluid (UAMMD's BDHI with open
// boundaries), Euler-Maruyama:
//   x += dt M F + sqrt(2 kT dt) M^{1/2} W,   W ~ N(0, I) of size 3N,
// M the RPY mobility of the group's particles (hydrodynamics/open_mobility.hpp). What differs between
// the methods is only how M^{1/2} W is made: BdhiCholesky (bdhi_cholesky.hpp) and BdhiLanczos
// (bdhi_lanczos.hpp) derive from BdhiOpenBoundary below.
// Particles outside the group neither move nor take part in the hydrodynamics (UAMMD's BDHI sees
// only its group); their forces still act on the group through the force field.
#include <cmath>

#include "hydrodynamics/open_mobility.hpp"
#include "integrators/bdhi_kernels.hpp"
#include "integrators/brownian.hpp"

namespace structmd {

struct BdhiOpenBoundaryInputs : IntegratorInputs {
    static constexpr bool oneFluid = true;
    static std::vector<Parameter> parameters() {
        return {number("viscosity", "mass/(length time)", Must::be_positive),
                with_default(number("hydrodynamicRadius", "length", Must::be_positive), 0.0)};
    }
    static constexpr bool needsRadius = true;  // without hydrodynamicRadius, each particle's radius
    static constexpr bool overdamped = true;
    static constexpr const char* radiusParameter = "hydrodynamicRadius";
};

template <class B, class R>
class BdhiOpenBoundary : public Integrator<B, R> {
public:
    BdhiOpenBoundary(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : Integrator<B, R>(scope),
          backend_(backend),
          rpy_{R(1.0 / v["viscosity"])},
          hydrodynamicRadius_(v["hydrodynamicRadius"]) {}

    bool overdamped() const override { return true; }

    // Overdamped particles have no velocity of their own: the kinetic energy reads 0.
    void begin(Particles<B, R>& p, ForceSource&) override {
        backend_.for_each(p.count, StopParticles<R>{p.vel.data(), this->scope().group});
    }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        const int64_t n = p.count;
        forces.update_forces();
        resize(n);
        backend_.for_each(n, PlaceSpheres<R>{spheres_.data(), p.pos.data(), p.image.data(), p.radius.data(), s.group,
                                             p.box, R(hydrodynamicRadius_)});
        backend_.for_each(n, FlattenForces<R>{p.force.data(), flatForce_.data()});
        backend_.for_each_lanes(n, MobilityProduct<R>{spheres_.data(), n, rpy_, flatForce_.data(), drift_.data()},
                                LaneSizing::kFillDevice);
        const bool thermal = s.kT > 0.0;
        if (thermal) {
            backend_.for_each(n, DrawHydrodynamicNoise<R>{s.group, p.noise, p.now(), gaussian_.data()});
            mobility_sqrt(n, p, gaussian_.data(), noise_.data());
        }
        backend_.for_each(n, BdhiMove<R>{p.pos.data(), p.image.data(), p.force.data(), drift_.data(),
                                         thermal ? noise_.data() : nullptr, nullptr, s.group, p.box, R(s.timeStep),
                                         R(std::sqrt(2.0 * s.kT * s.timeStep)), p.fault_slot(1), p.drift});
        forces.positions_moved(s.timeStep, true);
    }

protected:
    // noise = M^{1/2} w for the spheres of this step (spheres()), both flat arrays of 3n numbers.
    virtual void mobility_sqrt(int64_t n, Particles<B, R>& p, const R* w, R* noise) = 0;

    const B& backend() const { return backend_; }
    const Real4<R>* spheres() const { return spheres_.data(); }
    const RpyTensor<R>& rpy() const { return rpy_; }

private:
    void resize(int64_t n) {
        const size_t flat = static_cast<size_t>(3 * n);
        backend_.resize(spheres_, static_cast<size_t>(n));
        backend_.resize(flatForce_, flat);
        backend_.resize(drift_, flat);
        if (this->scope().kT > 0.0) {
            backend_.resize(gaussian_, flat);
            backend_.resize(noise_, flat);
        }
    }

    const B& backend_;
    RpyTensor<R> rpy_;
    double hydrodynamicRadius_;  // 0: each particle's radius
    typename B::template Buffer<Real4<R>> spheres_;
    typename B::template Buffer<R> flatForce_, drift_, gaussian_, noise_;
};

}  // namespace structmd
