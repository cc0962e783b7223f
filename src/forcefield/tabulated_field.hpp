#pragma once
// ["External","ExternalTabulated"] and ["External","PolarizationTabulated"]: an energy given on a
// periodic grid of nx x ny x nz cells spanning the box (cell (i, j, k) centred at
// ((i + 1/2) L_x/nx - L_x/2, ...), as UAMMD-structured's grid and its generator place them), times
// `scale`, interpolated at each particle with Peskin's three-point kernel as UAMMD-structured's
// immersed-boundary gather does:
//   U(x) = sum_cells E_c phi((x - x_c)/h_x) phi((y - y_c)/h_y) phi((z - z_c)/h_z),
//   phi(s) = (1 + sqrt(1 - 3 s^2)) / 3                        for |s| <= 1/2,
//            (5 - 3|s| - sqrt(1 - 3 (1 - |s|)^2)) / 6         for 1/2 <= |s| <= 3/2, else 0,
// and the force is exactly -grad U of that interpolant (phi is continuously differentiable), so
// energy and force agree; UAMMD-structured interpolates the table's force column separately, which
// matches this to the interpolation's accuracy when that column is the energy's gradient (as its
// generator makes it). The polarization field multiplies U and F of particle i by
// eps alpha_i, eps = dielectricConstant / (4 pi f) (f: the units' electric conversion factor) and
// alpha_i the state's polarizability. The grid follows the box: h = L / n at each evaluation.
// ["External","HelixBoundaries"] (helix_boundaries_read.cpp) is such a field made at load, times
// lambda^2 of the ensemble.
#include <cmath>
#include <memory>
#include <vector>

#include "core/box.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/interactor_build.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from the entry: the scaled energies, x fastest (cell i + nx (j + ny k)),
// and for the polarization field each particle's factor eps alpha_i (empty for ExternalTabulated).
struct TabulatedFieldConfig : ComponentConfig {
    int n[3] = {0, 0, 0};
    std::vector<double> energy;
    std::vector<double> factor;
    bool lambdaSquared = false;  // the field is scaled by the ensemble's lambda^2
};

// Peskin's three-point kernel phi(s) and its derivative, s in cells.
template <class R>
SMD_HD SMD_INLINE void peskin_three_point(R s, R& phi, R& dphi) {
    const R a = s < R(0) ? -s : s;
    const R sign = s < R(0) ? R(-1) : R(1);
    if (a <= R(0.5)) {
        const R root = sqrt(R(1) - R(3) * a * a);
        phi = (R(1) + root) / R(3);
        dphi = -s / root;
    } else if (a <= R(1.5)) {
        const R u = R(1) - a;
        const R root = sqrt(R(1) - R(3) * u * u);
        phi = (R(5) - R(3) * a - root) / R(6);
        dphi = sign * (R(-3) - R(3) * u / root) / R(6);
    } else {
        phi = R(0);
        dphi = R(0);
    }
}

// With lambda given, U and F are scaled by lambda^2; with LambdaDerivative, dU/dlambda = 2 lambda U
// goes to the energy output instead (no force).
template <class R, bool WantForce, bool WantEnergy, bool LambdaDerivative = false>
struct TabulatedFieldKernel {
    const Real4<R>* pos;
    const uint8_t* group;
    const R* energyGrid;
    const R* factor;  // null: 1 for every particle
    int nx, ny, nz;
    Box<R> box;
    ForceOutputs<R> out;
    const double* lambda;  // on the backend; null: no coupling

    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        const Vec3<R> x = xyz(pos[i]);
        const int n[3] = {nx, ny, nz};
        const R position[3] = {x.x, x.y, x.z};
        const R length[3] = {box.length.x, box.length.y, box.length.z};
        // Along each axis the three cells nearest to the particle (the kernel is zero beyond 3/2 cells)
        // with their weights and the weights' derivatives in length units.
        int cell[3][3];
        R w[3][3], dw[3][3];
        for (int a = 0; a < 3; ++a) {
            const R h = length[a] / R(n[a]);
            const R s = (position[a] + R(0.5) * length[a]) / h - R(0.5);  // in cells, centres at integers
            const R nearest = floor(s + R(0.5));
            for (int m = 0; m < 3; ++m) {
                const R c = nearest + R(m - 1);
                peskin_three_point(s - c, w[a][m], dw[a][m]);
                dw[a][m] /= h;
                int index = static_cast<int>(c) % n[a];
                cell[a][m] = index < 0 ? index + n[a] : index;
            }
        }
        R e = R(0);
        Vec3<R> gradient{R(0), R(0), R(0)};
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j)
                for (int m = 0; m < 3; ++m) {
                    const R value = energyGrid[cell[0][m] + nx * (cell[1][j] + ny * cell[2][k])];
                    e += w[0][m] * w[1][j] * w[2][k] * value;
                    gradient.x += dw[0][m] * w[1][j] * w[2][k] * value;
                    gradient.y += w[0][m] * dw[1][j] * w[2][k] * value;
                    gradient.z += w[0][m] * w[1][j] * dw[2][k] * value;
                }
        R scale = factor ? factor[i] : R(1);
        if (lambda && LambdaDerivative) scale *= R(2) * R(*lambda);
        else if (lambda) scale *= R(*lambda) * R(*lambda);
        add_to_outputs<WantForce, WantEnergy, false>(out, i, -scale * gradient, scale * e, zero_tensor<R>());
    }
};

template <class B, class R>
class TabulatedFieldInteraction : public Interactor<B, R> {
public:
    // lambda: the ensemble's, on the backend; read when the config asks for lambda^2.
    TabulatedFieldInteraction(const B& backend, InteractorScope scope, const TabulatedFieldConfig& config,
                              const double* lambda)
        : Interactor<B, R>(std::move(scope)),
          backend_(backend),
          n_{config.n[0], config.n[1], config.n[2]},
          lambda_(config.lambdaSquared ? lambda : nullptr) {
        const std::vector<R> energy(config.energy.begin(), config.energy.end());
        backend_.upload(energy_, energy.data(), energy.size());
        const std::vector<R> factor(config.factor.begin(), config.factor.end());
        backend_.upload(factor_, factor.data(), factor.size());
    }

    // A field exerts no force from another particle.
    bool has_pair_forces() const override { return true; }
    void add_pair_forces(Particles<B, R>&, int, Real4<R>*) override {}

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        ForceOutputs<R> own = out;
        own.virial = nullptr;
        dispatch_outputs(own, [&](auto force, auto energy, auto) {
            backend_.for_each(particles.count,
                              TabulatedFieldKernel<R, decltype(force)::value, decltype(energy)::value>{
                                  particles.pos.data(), this->group(), energy_.data(),
                                  factor_.empty() ? nullptr : factor_.data(), n_[0], n_[1], n_[2], particles.box,
                                  own, lambda_});
        });
    }

    bool couples_to_lambda() const override { return lambda_ != nullptr; }
    void add_lambda_derivative(Particles<B, R>& particles, R* perParticle) override {
        if (!lambda_) return;
        const ForceOutputs<R> out = energy_outputs(perParticle);
        backend_.for_each(particles.count, TabulatedFieldKernel<R, false, true, true>{
                                               particles.pos.data(), this->group(), energy_.data(),
                                               factor_.empty() ? nullptr : factor_.data(), n_[0], n_[1], n_[2],
                                               particles.box, out, lambda_});
    }

private:
    const B& backend_;
    int n_[3];
    const double* lambda_;
    typename B::template Buffer<R> energy_;
    typename B::template Buffer<R> factor_;
};

// ["External","ExternalTabulated"] (Polarization = false) and ["External","PolarizationTabulated"].
template <bool Polarization>
struct TabulatedFieldComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);  // tabulated_field_read.cpp

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        return std::make_unique<TabulatedFieldInteraction<B, R>>(build.backend, build.scope(s),
                                                                 static_cast<const TabulatedFieldConfig&>(*s.config),
                                                                 build.context.constants.lambda);
    }
};

// ["External","HelixBoundaries"]: a tube of radius helixInnerRadius around a helix along z, outside
// of which U = K (d - helixInnerRadius)^2 / 2 (d: the distance to the helix), tabulated at load on
// the grid of a tabulated field and scaled by lambda^2 (helix_boundaries_read.cpp).
struct HelixBoundariesComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);  // helix_boundaries_read.cpp

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        return TabulatedFieldComponent<false>::make_interactor<B, R, PairR>(build, s);
    }
};

}  // namespace structmd
