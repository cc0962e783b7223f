#pragma once
// ["SteepestDescent","SteepestDescent"]: energy minimisation. Each step moves x += (h / max|F|) F; a
// move that lowers the energy is kept and h grows by 1.001, one that raises it is undone and h
// shrinks by 0.999. Once max|F| < maxObjectiveForce the particles stay put. Steps advance the step
// counter only, not the time. Each step waits for two energies and a maximum on the host. With
// nStepsPrintProgress = k > 0 every k-th step logs max|F| and h at level info.
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "integrators/integrator.hpp"
#include "state/fault.hpp"

namespace structmd {

struct SteepestDescentInputs : IntegratorInputs {
    static std::vector<Parameter> parameters() {
        return {number("h", "length", Must::be_positive), number("maxObjectiveForce", "force", Must::be_positive),
                with_default(number("nStepsPrintProgress", "step", Must::be_integer), 0.0)};
    }
    static void validate(const ParameterValues& v, const std::string& path) {
        if (v["nStepsPrintProgress"] < 0.0)
            throw input_error(path + ".parameters.nStepsPrintProgress", "expected a number of steps >= 0 (0: never)");
    }
    static constexpr bool minimiser = true;
};

template <class R>
struct ForceMagnitude {
    const Real4<R>* force;
    const uint8_t* group;
    SMD_HD double operator()(int64_t i) const {
        if (group && !group[i]) return 0.0;
        const Real4<R> f = force[i];
        return sqrt(static_cast<double>(f.x) * f.x + static_cast<double>(f.y) * f.y + static_cast<double>(f.z) * f.z);
    }
};

template <class R>
struct DescentMove {
    Real4<R>* pos;
    Image* image;
    Real4<R>* savedPos;
    Image* savedImage;
    const Real4<R>* force;
    const uint8_t* group;
    Box<R> box;
    R stepPerForce;  // h / max|F|
    FaultSlot fault;
    SMD_HD void operator()(int64_t i) const {
        const Real4<R> p = pos[i];
        savedPos[i] = p;
        savedImage[i] = image[i];
        if (group && !group[i]) return;
        const Real4<R> f = force[i];
        const Real4<R> moved = displaced(p, stepPerForce * xyz(f), box, image[i]);
        pos[i] = moved;
        fault.check(i, moved, f);
    }
};

template <class R>
struct UndoMove {
    Real4<R>* pos;
    Image* image;
    const Real4<R>* savedPos;
    const Image* savedImage;
    SMD_HD void operator()(int64_t i) const {
        pos[i] = savedPos[i];
        image[i] = savedImage[i];
    }
};

template <class B, class R>
class SteepestDescent : public Integrator<B, R> {
public:
    SteepestDescent(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : Integrator<B, R>(scope),
          backend_(backend),
          initialH_(v["h"]),
          h_(initialH_),
          maxObjectiveForce_(v["maxObjectiveForce"]),
          progressInterval_(static_cast<int64_t>(v["nStepsPrintProgress"])) {}

    double time_advance() const override { return 0.0; }
    std::vector<double> state() const override { return {h_}; }
    void restore(const std::vector<double>& state) override { h_ = state.at(0); }

    void begin(Particles<B, R>& p, ForceSource&) override {
        h_ = initialH_;
        backend_.resize(savedPos_, p.count);
        backend_.resize(savedImage_, p.count);
    }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        forces.update_forces();
        const double largest = backend_.maximum(p.count, ForceMagnitude<R>{p.force.data(), this->scope().group});
        if (!std::isfinite(largest))
            throw Error(STRUCTMD_ERR_NUMERICAL, "step " + std::to_string(p.timeline.evaluating_step()) +
                                                    ": a force is not finite, steepest descent cannot move "
                                                    "(overlapping particles?)");
        const int64_t step = p.timeline.step();
        if (progressInterval_ > 0 && step % progressInterval_ == 0 && this->scope().log)
            this->scope().log->info("steepest descent " + this->scope().name + ", step " + std::to_string(step) +
                                    ": max|F| " + std::to_string(largest) + " (objective " +
                                    std::to_string(maxObjectiveForce_) + "), h " + std::to_string(h_));
        if (largest < maxObjectiveForce_ || largest == 0.0) return;  // converged
        const double before = forces.potential_energy();
        backend_.for_each(p.count, DescentMove<R>{p.pos.data(), p.image.data(), savedPos_.data(), savedImage_.data(),
                                                  p.force.data(), this->scope().group, p.box, R(h_ / largest),
                                                  p.fault_slot(1)});
        forces.positions_moved(0.0, false);
        const double after = forces.potential_energy();
        if (after < before) {
            h_ *= 1.001;
            return;
        }
        backend_.for_each(p.count, UndoMove<R>{p.pos.data(), p.image.data(), savedPos_.data(), savedImage_.data()});
        forces.positions_moved(0.0, false);
        h_ *= 0.999;
    }

private:
    const B& backend_;
    double initialH_;
    double h_;
    double maxObjectiveForce_;
    int64_t progressInterval_;  // 0: no progress lines
    typename B::template Buffer<Real4<R>> savedPos_;
    typename B::template Buffer<Image> savedImage_;
};

}  // namespace structmd
