// A structmd plugin: the Lennard-Jones force as a transverser, each particle's total force from its
// pairs, three values per particle (UAMMD's example of a Transverser):
//
//   U(r) = 4 epsilon ((sigma / r)^12 - (sigma / r)^6),   F_i = sum_j -U'(r_ij) (r_i - r_j) / r_ij
//
// over the pairs closer than the cutoff of structmd_traverse. epsilon (energy) and sigma (length) are
// its parameters, one pair for all types. Written once for every backend against the Transverser
// contract (transverser/transverser.hpp).
#include "engines/plugin.hpp"

namespace {

using namespace structmd;

struct LennardJonesForce {
    static constexpr int values = 3;
    static std::vector<Parameter> parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)};
    }

    template <class R>
    struct Functor {
        using Info = int;
        using Compute = Vec3<R>;
        R epsilon, sigma2;
        R* out;  // x, y, z by particle

        SMD_HD Vec3<R> zero() const { return {R(0), R(0), R(0)}; }
        SMD_HD int info(int) const { return 0; }
        SMD_HD Vec3<R> compute(const Real4<R>& ri, const Real4<R>& rj, int, int) const {
            const Vec3<R> rij = xyz(rj) - xyz(ri);  // r_j - r_i
            const R invR2 = R(1) / dot(rij, rij);
            const R s6 = sigma2 * sigma2 * sigma2 * invR2 * invR2 * invR2;  // (sigma / r)^6
            // -U'(r) / r = 24 epsilon (2 s^12 - s^6) / r^2, along r_i - r_j = -rij
            return (R(-24) * epsilon * (R(2) * s6 * s6 - s6) * invR2) * rij;
        }
        SMD_HD void accumulate(Vec3<R>& total, const Vec3<R>& current) const { total += current; }
        SMD_HD void set(int i, const Vec3<R>& total) const {
            out[3 * i] = total.x;
            out[3 * i + 1] = total.y;
            out[3 * i + 2] = total.z;
        }
    };

    template <class R>
    static Functor<R> make(const TransverserInputs<R>& in, const ParameterValues& v) {
        const double sigma = v["sigma"];
        return {R(v["epsilon"]), R(sigma * sigma), in.out};
    }
};

}  // namespace

STRUCTMD_PLUGIN(registrar) { registrar.transverser<LennardJonesForce>("LennardJonesForce"); }
