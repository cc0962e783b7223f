#pragma once
// ["NonBonded","DipolarMagnetic"]: point magnetic dipoles mu_i (magnetic_moment.hpp), cut at cutOff
// without shift. With k = permeability / (4 pi) and r = r_j - r_i,
//   B_j(r_i) = k [3 (mu_j . r) r / r^5 - mu_j / r^3],      U_ij = -mu_i . B_j(r_i)
//            = k [mu_i . mu_j / r^3 - 3 (mu_i . r)(mu_j . r) / r^5],
//   F_i = -dU/dr_i = -3 k / r^5 [(mu_i . mu_j) r + (mu_j . r) mu_i + (mu_i . r) mu_j
//                                - 5 (mu_i . r)(mu_j . r) r / r^2],
//   torque_i = mu_i x B_j(r_i),
// and the field B_j(r_i) itself for the magnetic integrators. Each particle sums its neighbours over
// a full list (as pair_kernel.hpp does): no atomics; energy and virial split equally between the two.
#include <memory>

#include "core/real_limits.hpp"
#include "core/lanes.hpp"
#include "forcefield/bonded_geometry.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/magnetic_moment.hpp"
#include "neighbour/neighbour_view.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

template <class R>
struct DipolarMagneticKernel {
    const Real4<R>* magnetization;
    const Real4<R>* dir;  // null: every particle at the identity
    const uint8_t* group;
    NeighbourView<R> neighbours;
    R k;  // permeability / (4 pi)
    R cutoff2;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t slot, Lanes lanes) const {
        using bonded_geometry::cross;
        const NeighbourView<R>& v = neighbours;
        const int i = v.order[slot];
        if (group && !group[i]) return;
        const Vec3<R> ri = xyz(v.positions[slot]);
        const Vec3<R> mui = magnetic_moment(magnetization, dir, i);
        Vec3<R> f{0, 0, 0}, b{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        v.for_each_neighbour(static_cast<int>(slot), [&](int s) {
            const int j = v.order[s];
            if (group && !group[j]) return;
            const Vec3<R> r = v.box.minimum_image(xyz(v.positions[s]) - ri);
            const R r2 = dot(r, r);
            // A coincident pair (r2 = 0) is not skipped: its terms come out NaN, which the step and
            // the getters report as NUMERICAL, as for every pair term.
            if (!(r2 < cutoff2)) return;
            const Vec3<R> muj = magnetic_moment(magnetization, dir, j);
            const R invR2 = reciprocal(r2);
            const R invR3 = sqrt(invR2) * invR2;
            const R invR5 = invR3 * invR2;
            const R miR = dot(mui, r), mjR = dot(muj, r);
            const Vec3<R> bj = k * ((R(3) * mjR * invR5) * r - invR3 * muj);
            b += bj;
            e -= R(0.5) * dot(mui, bj);
            const Vec3<R> fij = (R(-3) * k * invR5) * (dot(mui, muj) * r + mjR * mui + miR * muj -
                                                      (R(5) * miR * mjR * invR2) * r);
            f += fij;
            w += R(-0.5) * outer(r, fij);
        }, lanes);
        f = lanes.sum(f);
        b = lanes.sum(b);
        e = lanes.sum(e);
        w = lanes.sum(w);
        if (!lanes.leader()) return;
        if (out.force) accumulate(out.force[i], f);
        if (out.energy) out.energy[i] += e;
        if (out.virial) out.virial[i] += w;
        if (out.torque) accumulate(out.torque[i], cross(mui, b));
        if (out.magneticField) accumulate(out.magneticField[i], b);
    }
};

template <class B, class R>
class DipolarMagneticInteraction : public Interactor<B, R> {
public:
    DipolarMagneticInteraction(const B& backend, InteractorScope scope, std::shared_ptr<VerletList<B, R>> list,
                               R k, R cutoff)
        : Interactor<B, R>(std::move(scope)), backend_(backend), list_(std::move(list)), k_(k), cutoff2_(cutoff * cutoff) {}

    bool pairwise() const override { return true; }
    bool makes_magnetic_field() const override { return true; }
    void prepare(Particles<B, R>& p) override { list_->update(p.pos, p.count, p.box, p.version); }

    void compute(Particles<B, R>& p, const ForceOutputs<R>& out) override {
        if (!out.force && !out.energy && !out.virial && !out.torque && !out.magneticField) return;
        backend_.for_each_lanes(p.count, DipolarMagneticKernel<R>{p.magnetization.data(),
                                                                  p.dir.empty() ? nullptr : p.dir.data(), this->group(),
                                                                  list_->view(), k_, cutoff2_, out});
    }

private:
    const B& backend_;
    std::shared_ptr<VerletList<B, R>> list_;
    R k_, cutoff2_;
};

struct DipolarMagnetic {
    static ForceFieldComponent reader_entry(ComponentKey key);  // magnetic_field_read.cpp

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& pair = static_cast<const PairSpec&>(s);
        const double k = pair.shared["permeability"] / (4.0 * 3.14159265358979323846);
        return std::make_unique<DipolarMagneticInteraction<B, R>>(build.backend, build.scope(pair), build.listFor(pair),
                                                                  R(k), R(pair.shared["cutOff"]));
    }
};

}  // namespace structmd
