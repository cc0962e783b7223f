#pragma once
// ["DPD","Verlet"]: dissipative particle dynamics (Groot and Warren 1997) integrated by velocity
// Verlet (pair_verlet.hpp). Between particles closer than r_c, with r = r_i - r_j, e = r / |r|,
// w = 1 - |r| / r_c, v = v_i - v_j and xi_ij an N(0, 1) number shared by the pair and fresh each
// evaluation,
//   F_i += [a w - gamma w^2 (e . v) + sqrt(2 gamma k_B T / dt) w xi_ij] e,
// equal and opposite on j, so the momentum is conserved and the thermostat is local.
#include <cmath>

#include "core/lanes.hpp"
#include "integrators/pair_verlet.hpp"

namespace structmd {

struct DpdVerletInputs : PairVerletInputs {
    static std::vector<Parameter> parameters() {
        std::vector<Parameter> all = PairVerletInputs::parameters();
        all.push_back(number("cutOff", "length", Must::be_positive));
        all.push_back(number("gamma", "mass/time", Must::be_non_negative));
        all.push_back(number("alpha", "energy/length"));
        return all;
    }
};

template <class R>
struct DpdPairForces {
    NeighbourView<R> neighbours;
    const Real4<R>* vel;  // by particle
    const uint8_t* group;
    NoiseKey noiseKey;
    ClockView now;
    R cutoff, repulsion, gamma, noiseAmplitude;  // r_c, a, gamma, sqrt(2 gamma k_B T / dt)
    Real4<R>* out;                               // by particle

    SMD_HD void operator()(int64_t k, Lanes lanes) const {
        const NeighbourView<R>& v = neighbours;
        const int i = v.order[k];
        Vec3<R> f{0, 0, 0};
        if (!(group && !group[i])) {
            const Vec3<R> ri = xyz(v.positions[k]);
            const Vec3<R> vi = xyz(vel[i]);
            const uint64_t idI = global_id(noiseKey, i);
            const int64_t step = now.step();
            const R cutoff2 = cutoff * cutoff;
            v.for_each_neighbour(static_cast<int>(k), [&](int s) {
                const int j = v.order[s];
                if (group && !group[j]) return;
                const Vec3<R> rij = v.box.minimum_image(ri - xyz(v.positions[s]));
                const R r2 = dot(rij, rij);
                // Coincident particles have no direction between them: no force, as in UAMMD.
                if (!(r2 < cutoff2) || r2 == R(0)) return;
                const R r = sqrt(r2);
                const Vec3<R> e = (R(1) / r) * rij;
                const R w = R(1) - r / cutoff;
                const R xi = pair_gaussian<R>(noiseKey.seed, idI, global_id(noiseKey, j), step);
                f += (repulsion * w - gamma * w * w * dot(e, vi - xyz(vel[j])) + noiseAmplitude * w * xi) * e;
            }, lanes);
        }
        f = lanes.sum(f);
        if (lanes.leader()) out[i] = Real4<R>{f.x, f.y, f.z, R(0)};
    }
};

template <class B, class R>
class DpdVerlet : public PairVerlet<B, R> {
public:
    DpdVerlet(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : PairVerlet<B, R>(backend, scope, v, v["cutOff"]),
          cutoff_(v["cutOff"]),
          gamma_(v["gamma"]),
          repulsion_(v["alpha"]) {}

protected:
    void compute_pair_forces(Particles<B, R>& p, const NeighbourView<R>& neighbours, Real4<R>* out) override {
        const IntegratorScope& s = this->scope();
        const double noiseAmplitude = std::sqrt(2.0 * gamma_ * s.kT / s.timeStep);
        this->backend_.for_each_lanes(p.count, DpdPairForces<R>{neighbours, p.vel.data(), s.group, p.noise, p.now(),
                                                                R(cutoff_), R(repulsion_), R(gamma_),
                                                                R(noiseAmplitude), out});
    }

private:
    double cutoff_, gamma_, repulsion_;
};

}  // namespace structmd
