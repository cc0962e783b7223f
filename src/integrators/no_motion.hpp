#pragma once
// ["None","None"]: steps that move nothing. UAMMD-structured's inputs use it to run their measures
// (energies, forces, writers) on a configuration as given. Each step advances the step counter and
// the time by the time step, which is optional (0 without one); no force is computed for it.
#include "integrators/integrator.hpp"

namespace structmd {

struct NoMotionInputs : IntegratorInputs {
    static constexpr bool minimiser = true;  // in the sense the reader asks: it needs no time step
};

template <class B, class R>
class NoMotion : public Integrator<B, R> {
public:
    NoMotion(const B&, const IntegratorScope& scope, const ParameterValues&) : Integrator<B, R>(scope) {}

    // The positions stay; the step and time move on (terms active at the next step then apply).
    void step(Particles<B, R>&, ForceSource& forces) override { forces.positions_moved(this->time_advance(), false); }
};

}  // namespace structmd
