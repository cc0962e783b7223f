#pragma once
// ["BDHITriplyPeriodic","PositivelySplitEwald"]: Brownian dynamics with hydrodynamic interactions in
// a triply periodic box by the positively split Ewald method (Fiore, Balboa Usabiaga, Donev & Swan,
// J. Chem. Phys. 146, 124116 (2017)), Euler-Maruyama:
//   x += dt (M_near + M_far) F + sqrt(2 kT dt) (M_near^{1/2} W1 + M_far^{1/2} W2),
// M_near + M_far the periodic RPY mobility split by xi (psi) into two positive-definite parts:
// M_far on the mesh with its noise in the same pass (hydrodynamics/pse_far_field.hpp), M_near a pair
// sum over a neighbour list (hydrodynamics/pse_near_field.hpp) and its square root by the Lanczos
// iteration (hydrodynamics/lanczos_sqrt.hpp). W1 is keyed by the particles' global ids, W2 by the
// wave vectors. As in UAMMD, only the integrator's group takes part: particles outside it neither
// push the fluid nor are carried by it.
#include <cmath>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "hydrodynamics/lanczos_sqrt.hpp"
#include "hydrodynamics/pse_far_field.hpp"
#include "hydrodynamics/pse_near_field.hpp"
#include "integrators/bdhi_grid.hpp"
#include "integrators/bdhi_kernels.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

struct BdhiPositivelySplitEwaldInputs : IntegratorInputs {
    static constexpr bool oneFluid = true;
    static std::vector<Parameter> parameters() {
        return {number("viscosity", "mass/(length time)", Must::be_positive),
                with_default(number("hydrodynamicRadius", "length", Must::be_positive), 0.0),
                with_default(number("tolerance", "1", Must::be_positive), 1e-3),
                with_default(number("psi", "1/length", Must::be_positive), 0.5)};
    }
    static constexpr bool needsRadius = true;  // without hydrodynamicRadius, the particles' radius
    static constexpr bool overdamped = true;
    static constexpr const char* radiusParameter = "hydrodynamicRadius";
    static void validate(const ParameterValues& v, const std::string& path) { validate_grid_tolerance(v, path); }
    // The far field's grid; the near field's reach where the radius is given (else it is the
    // group's, known at the first step).
    static void validate_in_box(const ParameterValues& v, const std::array<double, 3>& box, const std::string& path) {
        require_periodic_box(box, path + ".type", "this integrator's fluid grid");
        make_pse_far_plan(box.data(), v["psi"], v["tolerance"], path);
        if (v["hydrodynamicRadius"] > 0.0)
            check_near_field_fits(pse_near_cutoff(v["hydrodynamicRadius"], v["psi"], v["tolerance"]), box.data(), path);
    }
    static void check_near_field_fits(double cutoff, const double box[3], const std::string& path) {
        for (int d = 0; d < 3; ++d)
            if (cutoff > 0.5 * box[d])
                throw input_error(path + ".parameters.psi",
                                  "the near field reaches 2 a + sqrt(-ln tolerance) / psi = " + std::to_string(cutoff) +
                                      ", more than half the box along " + std::string(1, "xyz"[d]) + " (" +
                                      std::to_string(0.5 * box[d]) + "): give a larger psi");
    }
};

// out = M_near v (flat vectors by particle), one list slot per call: the self block and the pairs
// within the cutoff, nearest images.
template <class R>
struct PseNearProduct {
    NeighbourView<R> view;
    PseNearTensor<R> tensor;
    const uint8_t* group;
    const R* v;
    R* out;
    SMD_HD void operator()(int64_t k) const {
        const int i = view.order[k];
        Vec3<R> sum{R(0), R(0), R(0)};
        if (!group || group[i]) {
            sum = tensor.self() * Vec3<R>{v[3 * i], v[3 * i + 1], v[3 * i + 2]};
            const Vec3<R> ri = xyz(view.positions[k]);
            view.for_each_neighbour(static_cast<int>(k), [&](int s) {
                const int j = view.order[s];
                if (group && !group[j]) return;
                const Vec3<R> d = view.box.minimum_image(xyz(view.positions[s]) - ri);
                sum += tensor.apply(d, Vec3<R>{v[3 * j], v[3 * j + 1], v[3 * j + 2]});
            });
        }
        out[3 * i] = sum.x;
        out[3 * i + 1] = sum.y;
        out[3 * i + 2] = sum.z;
    }
};

// (members, sum of radii, sum of squared radii) of the group, to find its one radius.
template <class R>
struct GroupRadii {
    const R* radius;
    const uint8_t* group;
    SMD_HD Vec3<double> operator()(int64_t i) const {
        if (group && !group[i]) return {0.0, 0.0, 0.0};
        const double r = static_cast<double>(radius[i]);
        return {1.0, r, r * r};
    }
};

template <class B, class R>
class BdhiPositivelySplitEwald : public GridBdhi<B, R> {
public:
    // More iterations than this mean a tolerance below what the precision can give.
    static constexpr int kMaxLanczosIterations = 100;
    // The near-field list's radius over its cutoff: the skin spares rebuilds while particles move
    // less than half of it.
    static constexpr double kListSkinFactor = 1.1;

    BdhiPositivelySplitEwald(const B& backend, const IntegratorScope& scope, const ParameterValues& v)
        : GridBdhi<B, R>(backend, scope), viscosity_(v["viscosity"]), radius_(v["hydrodynamicRadius"]),
          tolerance_(v["tolerance"]), xi_(v["psi"]),
          lanczos_(backend, v["tolerance"], kMaxLanczosIterations, "the near-field mobility of " + scope.name) {}

    void begin(Particles<B, R>& p, ForceSource& forces) override {
        GridBdhi<B, R>::begin(p, forces);
        list_->adapt();
    }

    void step(Particles<B, R>& p, ForceSource& forces) override {
        const IntegratorScope& s = this->scope();
        const int64_t n = p.count;
        prepare(p);
        forces.update_forces();
        mesh_->displace(p, s.group, s.timeStep, s.kT, green_, static_cast<uint64_t>(NoisePurpose::hydrodynamics) << 48,
                        farDisplacement_.data());
        list_->update(p.pos, n, p.box, ++positionsVersion_);
        backend_.for_each(n, FlattenForces<R>{p.force.data(), flatForce_.data()});
        near_product(n, flatForce_.data(), nearDrift_.data());
        const bool thermal = s.kT > 0.0;
        if (thermal) {
            backend_.for_each(n, DrawHydrodynamicNoise<R>{s.group, p.noise, p.now(), gaussian_.data()});
            lanczos_.apply_sqrt(3 * n, gaussian_.data(), nearNoise_.data(),
                                [&](const R* v, R* out) { near_product(n, v, out); });
        }
        backend_.for_each(n, BdhiMove<R>{p.pos.data(), p.image.data(), p.force.data(), nearDrift_.data(),
                                         thermal ? nearNoise_.data() : nullptr, farDisplacement_.data(), s.group,
                                         p.box, R(s.timeStep), R(std::sqrt(2.0 * s.kT * s.timeStep)),
                                         p.fault_slot(1), p.drift});
        forces.positions_moved(s.timeStep, true);
    }

private:
    void near_product(int64_t n, const R* v, R* out) {
        backend_.for_each(n, PseNearProduct<R>{list_->view(), near_, this->scope().group, v, out});
    }

    // The mesh, the near-field tensor and the list for the present box, made once: a box that
    // changes afterwards is refused.
    void prepare(const Particles<B, R>& p) override {
        const std::string& path = this->scope().path;
        const double box[3] = {double(p.box.length.x), double(p.box.length.y), double(p.box.length.z)};
        if (mesh_) {
            refuse_changed_box(this->scope(), box, mesh_->plan().box, 3,
                               "[\"BDHITriplyPeriodic\", \"PositivelySplitEwald\"]", "solves the Stokes flow");
        } else {
            const FcmPlan plan = make_pse_far_plan(box, xi_, tolerance_, path);
            const double radius = radius_ > 0.0 ? radius_ : group_radius(p);
            const double cutoff = pse_near_cutoff(radius, xi_, tolerance_);
            BdhiPositivelySplitEwaldInputs::check_near_field_fits(cutoff, box, path);
            near_ = make_pse_near_tensor<R>(radius, xi_, viscosity_, tolerance_);
            green_ = PseFarGreen<R>{R(1.0 / viscosity_), R(radius), R(0.25 / (xi_ * xi_)), R(plan.sigma * plan.sigma)};
            mesh_ = std::make_unique<FcmMesh<B, R, PseFarGreen<R>>>(backend_, plan);
            list_ = std::make_unique<VerletList<B, R>>(backend_, cutoff, kListSkinFactor, PairCondition::all,
                                                       PairFilterInputs{}, nullptr, 1, nullptr);
        }
        const size_t flat = static_cast<size_t>(3 * p.count);
        for (auto* buffer : {&farDisplacement_, &flatForce_, &nearDrift_}) backend_.resize(*buffer, flat);
        if (this->scope().kT > 0.0)
            for (auto* buffer : {&gaussian_, &nearNoise_}) backend_.resize(*buffer, flat);
    }

    // The Ewald split is for spheres of one radius: without hydrodynamicRadius, the group's
    // particles must share theirs.
    double group_radius(const Particles<B, R>& p) const {
        const Vec3<double> sums = backend_.template reduce<Vec3<double>>(
            p.count, GroupRadii<R>{p.radius.data(), this->scope().group}, {0.0, 0.0, 0.0});
        if (sums.x == 0.0) return 1.0;  // an empty group moves nothing: any radius will do
        const double mean = sums.y / sums.x;
        const double spread = std::sqrt(std::fmax(sums.z / sums.x - mean * mean, 0.0));
        if (!(spread <= 1e-6 * mean))
            throw input_error(this->scope().path + ".parameters.hydrodynamicRadius",
                              "missing: the particles of the group have different radii (mean " + std::to_string(mean) +
                                  ", spread " + std::to_string(spread) +
                                  "), and the positively split Ewald sum is for spheres of one radius: give it here");
        return mean;
    }

    using GridBdhi<B, R>::backend_;
    double viscosity_, radius_, tolerance_, xi_;
    LanczosSqrt<B, R> lanczos_;
    PseNearTensor<R> near_{};
    PseFarGreen<R> green_{};
    std::unique_ptr<FcmMesh<B, R, PseFarGreen<R>>> mesh_;
    std::unique_ptr<VerletList<B, R>> list_;
    int64_t positionsVersion_ = 0;
    typename B::template Buffer<R> farDisplacement_, flatForce_, nearDrift_, gaussian_, nearNoise_;
};

}  // namespace structmd
