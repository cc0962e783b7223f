#pragma once
// ["BDHIOpenBoundary","Lanczos"]: the noise M^{1/2} W by the Lanczos iteration
// (hydrodynamics/lanczos_sqrt.hpp) on the matrix-free product M v, an O(N^2) pair sum of RPY blocks:
// no 3N x 3N matrix is stored, and each iteration costs one product. It approximates the symmetric
// square root to the relative `tolerance`.
#include "hydrodynamics/lanczos_sqrt.hpp"
#include "integrators/bdhi_open_boundary.hpp"

namespace structmd {

struct BdhiLanczosInputs : BdhiOpenBoundaryInputs {
    static std::vector<Parameter> parameters() {
        std::vector<Parameter> all = BdhiOpenBoundaryInputs::parameters();
        all.push_back(with_default(number("tolerance", "dimensionless", Must::be_positive), 1e-3));
        return all;
    }
};

template <class B, class R>
class BdhiLanczos : public BdhiOpenBoundary<B, R> {
public:
    // More iterations than this mean a tolerance below what the precision can give.
    static constexpr int kMaxIterations = 100;

    BdhiLanczos(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : BdhiOpenBoundary<B, R>(backend, scope, v),
          lanczos_(backend, v["tolerance"], kMaxIterations, "the mobility of " + scope.name) {}

protected:
    void mobility_sqrt(int64_t n, Particles<B, R>&, const R* w, R* noise) override {
        lanczos_.apply_sqrt(3 * n, w, noise, [&](const R* v, R* out) {
            this->backend().for_each_lanes(n, MobilityProduct<R>{this->spheres(), n, this->rpy(), v, out},
                                           LaneSizing::kFillDevice);
        });
    }

private:
    LanczosSqrt<B, R> lanczos_;
};

}  // namespace structmd
