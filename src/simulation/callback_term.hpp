#pragma once
// The host's force callbacks as a term of the force field: called once per configuration (positions
// version), their forces kept on the backend and added at every force evaluation at those positions,
// their energy and virial kept for the energy and virial getters.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "simulation/engine_functors.hpp"
#include "simulation/force_callbacks.hpp"
#include "simulation/host_transfer.hpp"
#include "state/particles.hpp"

namespace structmd {

template <class R>
struct AddForces {
    const Real4<R>* extra;
    Real4<R>* force;
    SMD_HD void operator()(int64_t i) const {
        force[i].x += extra[i].x;
        force[i].y += extra[i].y;
        force[i].z += extra[i].z;
    }
};

template <class B, class R>
class CallbackTerm {
public:
    void set_host(HostForceCallback callback) {
        host_ = std::move(callback);
        version_ = kNone;
    }
    void set_device(DeviceForceCallback callback) {
        device_ = std::move(callback);
        version_ = kNone;
    }
    bool empty() const { return !host_ && !device_; }

    // Calls the callbacks for p's positions unless they have seen them. A callback that throws or
    // gives a non-finite value leaves the term stale, so the next evaluation calls it again.
    void evaluate(const B& backend, Particles<B, R>& p) {
        if (empty() || version_ == p.version) return;
        backend.resize(force_, p.count);
        double energy = 0.0;
        std::array<double, 9> virial{};
        const int64_t step = p.timeline.evaluating_step();
        if (host_) {
            std::vector<Real4<R>> packed(p.count);
            backend.download(p.pos, packed.data(), packed.size());
            std::vector<double> xyz(3 * p.count);
            unpack_vectors(packed.data(), p.count, xyz.data());
            std::vector<double> f(3 * p.count, 0.0);
            host_({xyz.data(), f.data(), p.count, &energy, virial.data(), step});
            for (int64_t k = 0; k < 3 * p.count; ++k)
                if (!std::isfinite(f[k]))
                    throw Error(STRUCTMD_ERR_CALLBACK, "step " + std::to_string(step) + ": the force callback gave "
                                                       "particle id " + std::to_string(k / 3) + " a force that is not finite");
            for (int64_t i = 0; i < p.count; ++i) packed[i] = {R(f[3 * i]), R(f[3 * i + 1]), R(f[3 * i + 2]), R(0)};
            backend.upload(force_, packed.data(), packed.size());
        } else {
            backend.fill(force_, Real4<R>{R(0), R(0), R(0), R(0)});
        }
        if (device_)
            device_({p.pos.data(), force_.data(), p.count, static_cast<int>(sizeof(R)), &energy, virial.data(), step,
                     backend.host_launch_stream()});
        require_finite(energy, "energy", step);
        for (double w : virial) require_finite(w, "virial", step);
        energy_ = energy;
        virial_ = virial;
        version_ = p.version;
    }

    // Adds the forces of the last evaluate() to `force`.
    void add_forces(const B& backend, Particles<B, R>& p) const {
        backend.for_each(p.count, AddForces<R>{force_.data(), p.force.data()});
    }
    double energy() const { return empty() ? 0.0 : energy_; }
    const std::array<double, 9>& virial() const { return virial_; }

private:
    static constexpr int64_t kNone = -1;

    static void require_finite(double value, const char* what, int64_t step) {
        if (!std::isfinite(value))
            throw Error(STRUCTMD_ERR_CALLBACK,
                        "step " + std::to_string(step) + ": the force callbacks gave a " + what + " that is not finite");
    }

    HostForceCallback host_;
    DeviceForceCallback device_;
    typename B::template Buffer<Real4<R>> force_;
    double energy_ = 0.0;
    std::array<double, 9> virial_{};
    int64_t version_ = kNone;
};

}  // namespace structmd
