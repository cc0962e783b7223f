#pragma once
// A simulationStep entry: something that fires at an interval of steps (a measure, a writer). It sees
// the simulation only through its interface, so one implementation serves every backend.
#include <cstdint>
#include <limits>
#include <string>

#include "simulation/simulation.hpp"

namespace structmd {

class SimulationStep {
public:
    SimulationStep(std::string name, int64_t interval, int64_t start, int64_t end)
        : name_(std::move(name)), interval_(interval), start_(start), end_(end) {}
    virtual ~SimulationStep() = default;

    const std::string& name() const { return name_; }
    // Whether the step reads exact second derivatives (Simulation::hessian_column): the force field
    // then makes them.
    virtual bool needs_hessian() const { return false; }
    // Whether it reads the forces between pairs (Simulation::pair_forces_on): every term must split them.
    virtual bool needs_pair_forces() const { return false; }

    // Fires when start <= step <= end and step is a multiple of the interval; the state the
    // schedule ends in is given to every step whose window holds it.
    bool in_window(int64_t step) const { return step >= start_ && step <= end_; }
    bool due(int64_t step) const { return in_window(step) && step % interval_ == 0; }

    // Runs the step for the current state once per step number, however often it is asked.
    void fire(Simulation& sim) {
        const int64_t step = sim.current_step();
        if (step == lastFired_) return;
        lastFired_ = step;
        run(sim);
    }

protected:
    virtual void run(Simulation& sim) = 0;

private:
    std::string name_;
    int64_t interval_;
    int64_t start_;
    int64_t end_;
    int64_t lastFired_ = std::numeric_limits<int64_t>::min();
};

}  // namespace structmd
