#pragma once
// UAMMD-structured's ["NonBonded","Zhang"]: the one-particle-thick membrane model of Yuan, Huang, Li,
// Lykotrafitis and Zhang (Phys. Rev. E 82, 011905, 2010), between particles with orientations. Each
// particle's director n is its body axis `axis` (body coordinates, default z) in the lab frame. For a
// pair at r = r_j - r_i, d = |r|, u = r/d, with per-type-pair epsilon, mu, chi, theta and
// r_b = 2^(7/6) radius, r_c = 5.2 radius:
//   a   = (n_i x u).(n_j x u) - sin(theta) (n_j - n_i).u - sin^2(theta)
//   phi = 1 + mu (a - 1)
//   U   = eps [(r_b/d)^4 - 2 (r_b/d)^2] + (1 - phi) eps                    for d < r_b
//   U   = -eps cos^(2 chi)(pi (d - r_b) / (2 (r_c - r_b))) phi               for r_b <= d < r_c
// with the signs of UAMMD-structured's code. Forces and torques are the exact derivatives: F_i =
// dU/dr, F_j = -F_i, and tau_i = dU/dn_i x n_i (a rotation omega of i changes n_i by omega x n_i).
// Each particle of the pair books half the energy. The neighbour list visits every pair from both
// particles; each keeps its own force and torque.
#include <cmath>
#include <memory>
#include <vector>

#include "core/quaternion.hpp"
#include "forcefield/bonded_geometry.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/interactor_tables.hpp"
#include "forcefield/pair_kernel.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from the entry: the body axis of the directors.
struct ZhangConfig : ComponentConfig {
    Vec3<double> axis{0.0, 0.0, 1.0};
};

struct ZhangPotential {
    template <class R>
    struct Params {
        R epsilon, mu, chi, sinTheta;
        R rb, rc;
        R cutoff2;  // rc^2; 0 for a type pair that does not interact
    };

    static std::vector<Parameter> pair_parameters() {
        return {number("radius", "length", Must::be_positive), number("epsilon", "energy"), number("mu", "1"),
                number("chi", "1", Must::be_positive), number("theta", "radians")};
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v) {
        const double radius = v["radius"];
        const double rc = 5.2 * radius;
        return {R(v["epsilon"]), R(v["mu"]), R(v["chi"]), R(std::sin(v["theta"])),
                R(std::pow(2.0, 7.0 / 6.0) * radius), R(rc), R(rc * rc)};
    }

    // The energy of the pair, the force on i (dU/dr) and the torque on i. U is symmetric in the two
    // particles (a(-u, n_j, n_i) = a(u, n_i, n_j)), so j's own call gives its force and torque.
    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>& r, const Vec3<R>& ni, const Vec3<R>& nj, const Params<R>& p,
                                       Vec3<R>& forceOnI, Vec3<R>& torqueOnI) {
        const R d = sqrt(dot(r, r));
        forceOnI = torqueOnI = {R(0), R(0), R(0)};
        if (!(d < p.rc) || !(d > R(0))) return R(0);
        const Vec3<R> u = (R(1) / d) * r;
        const R s = p.sinTheta;
        const R niu = dot(ni, u), nju = dot(nj, u);
        const R a = dot(ni, nj) - niu * nju - s * (nju - niu) - s * s;
        const R phi = R(1) + p.mu * (a - R(1));
        // da/du, its part across u over d (the gradient in r), and da/dn_i.
        const Vec3<R> dadu = (-nju) * ni - niu * nj - s * (nj - ni);
        const Vec3<R> gradA = (R(1) / d) * (dadu - dot(dadu, u) * u);
        const Vec3<R> dadni = nj - nju * u + s * u;
        R energy, radial, weight;  // U, the radial part of dU/dd, and the factor of a in U
        if (d < p.rb) {
            const R x2 = p.rb * p.rb / (d * d);
            energy = p.epsilon * (x2 * x2 - R(2) * x2) + (R(1) - phi) * p.epsilon;
            radial = p.epsilon * (R(-4) * x2 * x2 + R(4) * x2) / d;
            weight = -p.epsilon * p.mu;
        } else {
            const R angle = R(M_PI / 2) * (d - p.rb) / (p.rc - p.rb);
            const R c = cos(angle);
            const R attraction = -p.epsilon * pow(c, R(2) * p.chi);
            energy = attraction * phi;
            radial = p.epsilon * p.chi * R(M_PI) / (p.rc - p.rb) * pow(c, R(2) * p.chi - R(1)) * sin(angle) * phi;
            weight = attraction * p.mu;
        }
        forceOnI = radial * u + weight * gradA;
        torqueOnI = bonded_geometry::cross(weight * dadni, ni);
        return energy;
    }
};

template <class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct ZhangKernel {
    using Params = ZhangPotential::Params<R>;
    const Real4<R>* dir;  // by particle
    const uint8_t* group;
    NeighbourView<R> neighbours;
    PairTable<Params> table;
    Vec3<R> axis;  // the director in body coordinates
    ForceOutputs<R> out;

    SMD_HD Vec3<R> director(int particle) const {
        const Real4<R> q = dir[particle];
        return axis.x * body_x(q) + axis.y * body_y(q) + axis.z * body_z(q);
    }

    SMD_HD void operator()(int64_t k, Lanes lanes) const {
        const NeighbourView<R>& v = neighbours;
        const int i = v.order[k];
        if (group && !group[i]) return;
        const Real4<R> pi = v.positions[k];
        const Vec3<R> ri = xyz(pi);
        const Vec3<R> ni = director(i);
        const Params* row = table.row_of(i, static_cast<int>(pi.w));
        Vec3<R> f{0, 0, 0}, t{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        v.for_each_neighbour(static_cast<int>(k), [&](int s) {
            const Real4<R> pj = v.positions[s];
            const int j = v.order[s];
            const Vec3<R> rij = v.box.minimum_image(xyz(pj) - ri);
            const Params& p = row[static_cast<int>(pj.w)];
            if (!(dot(rij, rij) < p.cutoff2) || (group && !group[j])) return;
            Vec3<R> force, torque;
            const R energy = ZhangPotential::compute(rij, ni, director(j), p, force, torque);
            if (WantForce) {
                f += force;
                t += torque;
            }
            if (WantEnergy) e += R(0.5) * energy;
            if (WantVirial) w += R(-0.5) * outer(rij, force);
        }, lanes);
        if (WantForce) {
            f = lanes.sum(f);
            t = lanes.sum(t);
        }
        if (WantEnergy) e = lanes.sum(e);
        if (WantVirial) w = lanes.sum(w);
        if (!lanes.leader()) return;
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w, t);
    }
};

template <class B, class R>
class ZhangInteraction : public Interactor<B, R> {
public:
    using Params = ZhangPotential::Params<R>;

    // batch: the particles' batches when the table has one ntypes x ntypes block per batch, else null.
    ZhangInteraction(const B& backend, InteractorScope scope, std::shared_ptr<VerletList<B, R>> list,
                     const std::vector<Params>& table, int ntypes, const int* batch, const Vec3<R>& axis)
        : Interactor<B, R>(std::move(scope)),
          backend_(backend),
          list_(std::move(list)),
          ntypes_(ntypes),
          batch_(batch),
          axis_(axis) {
        backend_.upload(table_, table.data(), table.size());
    }

    bool pairwise() const override { return true; }
    void prepare(Particles<B, R>& p) override { list_->update(p.pos, p.count, p.box, p.version); }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        const NeighbourView<R> view = list_->view();
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            backend_.for_each_lanes(particles.count,
                                    ZhangKernel<R, decltype(force)::value, decltype(energy)::value,
                                                decltype(virial)::value>{particles.dir.data(), this->group(), view,
                                                                         PairTable<Params>{table_.data(), ntypes_,
                                                                                           batch_},
                                                                         axis_, out});
        });
    }

private:
    const B& backend_;
    std::shared_ptr<VerletList<B, R>> list_;
    typename B::template Buffer<Params> table_;
    int ntypes_;
    const int* batch_;
    Vec3<R> axis_;
};

struct ZhangComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);  // zhang_read.cpp

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& pair = static_cast<const PairSpec&>(s);
        const auto& config = static_cast<const ZhangConfig&>(*s.config);
        const auto table = pair_table_of<ZhangPotential::Params<R>>(
            pair, build.context, [](const ParameterValues& v) { return ZhangPotential::make_params<R>(v); });
        return std::make_unique<ZhangInteraction<B, R>>(build.backend, build.scope(pair), build.listFor(pair), table,
                                                        static_cast<int>(build.context.ntypes),
                                                        batches_for(build, pair), Vec3<R>{R(config.axis.x), R(config.axis.y), R(config.axis.z)});
    }
};

}  // namespace structmd
