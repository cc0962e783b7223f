#pragma once
// The step and the simulation time, with one owner. The host keeps three views of them:
//   committed:  the last step completed, what the API and the simulation steps see;
//   evaluating: the step whose forces and fields are being computed (one ahead once an integrator
//               has moved the particles to the next step's positions);
//   launched:   what the backend's clock (step_clock.hpp) holds when the next kernel runs.
// Kernels read the backend's clock plus the offset evaluating - launched, so their arguments stay
// the same from step to step and a recorded batch of steps replays as is.
#include <cstdint>

#include "state/step_clock.hpp"

namespace structmd {

class Timeline {
public:
    // All three views at (step, time); the backend's clock must be set to launched() too.
    void reset(int64_t step, double time) { committed_ = evaluating_ = launched_ = {step, time}; }

    int64_t step() const { return committed_.step; }
    double time() const { return committed_.time; }
    int64_t evaluating_step() const { return evaluating_.step; }
    double evaluating_time() const { return evaluating_.time; }
    const StepClock& launched() const { return launched_; }

    // The particles stand at the next step's positions, `elapsed` later.
    void positions_moved(double elapsed) { evaluating_ = {committed_.step + 1, committed_.time + elapsed}; }

    // The step is complete, `elapsed` later; the backend's clock advances alike (AdvanceClock) in
    // the same stream.
    void commit(double elapsed) { committed_ = evaluating_ = launched_ = {committed_.step + 1, committed_.time + elapsed}; }

    ClockView view(const StepClock* clock) const {
        return {clock, evaluating_.step - launched_.step, evaluating_.time - launched_.time};
    }

private:
    StepClock committed_, evaluating_, launched_;
};

}  // namespace structmd
