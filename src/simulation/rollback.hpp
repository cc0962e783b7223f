#pragma once
// The state a step call starts from, kept on the backend (one device copy per call), so that a
// blow-up found at the end of the call can be undone: the getters then show the last good state
// and the host can go on from it.
#include <cstdint>
#include <memory>
#include <vector>

#include "integrators/integrator.hpp"
#include "simulation/engine_functors.hpp"
#include "state/particles.hpp"

namespace structmd {

template <class B, class R>
class Rollback {
public:
    using Integrators = std::vector<std::unique_ptr<Integrator<B, R>>>;

    void save(const B& backend, Particles<B, R>& p, int activeStage, const Integrators& integrators) {
        backend.resize(pos_, p.count);
        backend.resize(vel_, p.count);
        backend.resize(image_, p.count);
        if (!p.dir.empty()) backend.resize(dir_, p.count);
        if (!p.magnetization.empty()) backend.resize(magnetization_, p.count);
        backend.for_each(p.count, CopyState<R>{p.pos.data(), p.image.data(), p.vel.data(), pos_.data(), image_.data(),
                                               vel_.data(), p.dir.data(), dir_.data(), p.magnetization.data(),
                                               magnetization_.data()});
        step_ = p.timeline.step();
        time_ = p.timeline.time();
        activeStage_ = activeStage;
        integrators_.clear();
        for (const auto& integrator : integrators) integrators_.push_back(integrator->state());
    }

    // Puts back positions, images, velocities, orientations, magnetic moments and the integrators' state; returns the schedule stage
    // and leaves p.timeline at the saved step (the caller sets the backend's clock to it).
    int restore(const B& backend, Particles<B, R>& p, Integrators& integrators) const {
        backend.for_each(p.count, CopyState<R>{pos_.data(), image_.data(), vel_.data(), p.pos.data(), p.image.data(),
                                               p.vel.data(), dir_.data(), p.dir.data(), magnetization_.data(),
                                               p.magnetization.data()});
        for (size_t k = 0; k < integrators.size(); ++k) integrators[k]->restore(integrators_[k]);
        p.timeline.reset(step_, time_);
        return activeStage_;
    }

private:
    typename B::template Buffer<Real4<R>> pos_, vel_;
    typename B::template Buffer<Image> image_;
    typename B::template Buffer<Real4<R>> dir_;  // sized once the particles have orientations
    typename B::template Buffer<Real4<R>> magnetization_;  // sized when the particles have magnetic moments
    int64_t step_ = 0;
    double time_ = 0.0;
    int activeStage_ = -1;
    std::vector<std::vector<double>> integrators_;
};

}  // namespace structmd
