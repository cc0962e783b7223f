#pragma once
// ["SPH","Verlet"]: smoothed particle hydrodynamics (Monaghan 2005) integrated by velocity Verlet
// (pair_verlet.hpp). With W the cubic spline of smoothing length h (cubic_spline_kernel.hpp), each
// evaluation first interpolates the density and the pressure of every particle,
//   rho_i = sum_j m_j W(|r_i - r_j|)   (j = i included),     P_i = K (rho_i - rho_0),
// then, with r = r_i - r_j, v = v_i - v_j and the artificial viscosity
// Pi_ij = -nu (v . r) / (|r|^2 + 0.001 h^2),
//   F_i = -sum_{j != i} m_i m_j (P_i / rho_i^2 + P_j / rho_j^2 + Pi_ij) grad_i W(|r_i - r_j|),
// equal and opposite on j, so the momentum is conserved.
#include "core/lanes.hpp"
#include "integrators/cubic_spline_kernel.hpp"
#include "integrators/pair_verlet.hpp"

namespace structmd {

struct SphVerletInputs : PairVerletInputs {
    static std::vector<Parameter> parameters() {
        std::vector<Parameter> all = PairVerletInputs::parameters();
        all.push_back(number("support", "length", Must::be_positive));
        all.push_back(number("viscosity", "length^5/(mass time)", Must::be_non_negative));
        all.push_back(number("gasStiffness", "energy/mass"));
        all.push_back(number("restDensity", "mass/length^3", Must::be_non_negative));
        return all;
    }
};

// P_i / rho_i^2 for the force pass, by particle.
template <class R>
struct SphDensities {
    NeighbourView<R> neighbours;
    const Real4<R>* vel;  // by particle; the mass in w
    const uint8_t* group;
    CubicSplineKernel<R> kernel;
    R stiffness, restDensity;
    R* pressureOverDensity2;  // by particle

    SMD_HD void operator()(int64_t k, Lanes lanes) const {
        const NeighbourView<R>& v = neighbours;
        const int i = v.order[k];
        if (group && !group[i]) return;
        const Vec3<R> ri = xyz(v.positions[k]);
        const R support2 = kernel.support() * kernel.support();
        R rho = 0;
        v.for_each_neighbour(static_cast<int>(k), [&](int s) {
            const int j = v.order[s];
            if (group && !group[j]) return;
            const Vec3<R> rij = v.box.minimum_image(ri - xyz(v.positions[s]));
            const R r2 = dot(rij, rij);
            if (!(r2 < support2)) return;
            rho += vel[j].w * kernel.value(sqrt(r2));
        }, lanes);
        rho = lanes.sum(rho);
        if (!lanes.leader()) return;
        rho += vel[i].w * kernel.value(R(0));
        pressureOverDensity2[i] = stiffness * (rho - restDensity) / (rho * rho);
    }
};

template <class R>
struct SphForces {
    NeighbourView<R> neighbours;
    const Real4<R>* vel;  // by particle; the mass in w
    const uint8_t* group;
    CubicSplineKernel<R> kernel;
    R viscosity;
    const R* pressureOverDensity2;  // by particle
    Real4<R>* out;                  // by particle

    SMD_HD void operator()(int64_t k, Lanes lanes) const {
        const NeighbourView<R>& v = neighbours;
        const int i = v.order[k];
        Vec3<R> f{0, 0, 0};
        if (!(group && !group[i])) {
            const Vec3<R> ri = xyz(v.positions[k]);
            const Vec3<R> vi = xyz(vel[i]);
            const R pi = pressureOverDensity2[i];
            const R support2 = kernel.support() * kernel.support();
            const R softening = R(0.001) * kernel.h * kernel.h;
            v.for_each_neighbour(static_cast<int>(k), [&](int s) {
                const int j = v.order[s];
                if (group && !group[j]) return;
                const Vec3<R> rij = v.box.minimum_image(ri - xyz(v.positions[s]));
                const R r2 = dot(rij, rij);
                if (!(r2 < support2)) return;
                const R artificialViscosity = -viscosity * dot(vi - xyz(vel[j]), rij) / (r2 + softening);
                const R strength = vel[j].w * (pi + pressureOverDensity2[j] + artificialViscosity);
                f -= (strength * kernel.derivative_over_r(sqrt(r2))) * rij;
            }, lanes);
        }
        f = lanes.sum(f);
        if (!lanes.leader()) return;
        const R mi = vel[i].w;
        out[i] = Real4<R>{mi * f.x, mi * f.y, mi * f.z, R(0)};
    }
};

template <class B, class R>
class SphVerlet : public PairVerlet<B, R> {
public:
    SphVerlet(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : PairVerlet<B, R>(backend, scope, v, 2.0 * v["support"]),
          h_(v["support"]),
          viscosity_(v["viscosity"]),
          stiffness_(v["gasStiffness"]),
          restDensity_(v["restDensity"]) {}

protected:
    void compute_pair_forces(Particles<B, R>& p, const NeighbourView<R>& neighbours, Real4<R>* out) override {
        const IntegratorScope& s = this->scope();
        if (static_cast<int64_t>(pressureOverDensity2_.size()) != p.count)
            this->backend_.resize(pressureOverDensity2_, p.count);
        const CubicSplineKernel<R> kernel{R(h_)};
        this->backend_.for_each_lanes(p.count, SphDensities<R>{neighbours, p.vel.data(), s.group, kernel, R(stiffness_),
                                                               R(restDensity_), pressureOverDensity2_.data()});
        this->backend_.for_each_lanes(p.count, SphForces<R>{neighbours, p.vel.data(), s.group, kernel, R(viscosity_),
                                                            pressureOverDensity2_.data(), out});
    }

private:
    double h_, viscosity_, stiffness_, restDensity_;
    typename B::template Buffer<R> pressureOverDensity2_;
};

}  // namespace structmd
