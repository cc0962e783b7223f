#pragma once
// Terms on the centres of mass of sets of particles: UAMMD-structured's Set1 (one set per row,
// "idSet_i") and Set2 (two sets per row, "idSet_i" and "idSet_j") components, generic in their
// potential (set_potentials.hpp).
//
// Centre of a set: C = sum w_k x_k / sum w_k with w_k the member's mass (every member weighs 1 when
// the set's total mass is zero, as for Brownian inputs), where each x_k is the member's position
// unwrapped next to the set's first member (x_k = x_0 + minimum_image(r_k - r_0)): the centre of a set
// split by the box is that of the whole set, and moving a particle across the box does not move it.
// A set must therefore span less than half the box along each axis (UAMMD-structured sums the
// positions as it stores them, never wrapped). The potential sees the centres as a bond sees its
// particles: the first wrapped into the box, the second its minimum image.
//
// A force F on a centre reaches member k as (w_k / sum w) F, so the centre feels exactly F and the
// term's energy and its per-member shares (a share w_k / sum w of U / sets) sum to U. A torque T on a
// set (UAMMD-structured's construction) reaches member k as
//   f_k = w_k (T x u_k) / sum_j w_j |u_j|^2,   u_k = d_k - (d_k . T) T / |T|^2,   d_k = x_k - C,
// u_k being the member's offset from the axis through C along T: the forces sum to zero (sum w_k d_k
// = 0) and their torque about C has component |T| along T (exactly T when the set is symmetric about
// that axis; a general set also feels its products of inertia about the axis). The virial of a member
// is its share of r_10 (x) F_1 for two-set forces, d_k (x) f_k for torques, none for one-set forces
// (a field, as External terms).
//
// Two kernels per evaluation, no host synchronisation: one thread per row sums its sets' centres and
// evaluates the potential into backend memory; then one thread per member reads its row's result and
// writes its own force. The reader refuses a particle in two sets of one entry, so no two threads
// write one particle.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "forcefield/bond_potential.hpp"
#include "forcefield/bonded_geometry.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/hessian_kernels.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/set_potentials.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from a Set entry's table (set_read.cpp).
struct SetConfig : ComponentConfig {
    int sets = 1;                   // sets per row
    std::vector<int> members;       // the particle ids of every set, row by row, set by set
    std::vector<int> start;         // set k (= row * sets + s) is members[start[k] .. start[k + 1])
    std::vector<Parameter> schema;  // the row's parameters, in the layout of `values`
    std::vector<double> values;     // width_of(schema) numbers per row
};

// A set's centre and what its members need from the row's evaluation.
template <class R>
struct SetCentre {
    Vec3<R> centre;  // unwrapped next to the set's first member
    R weight;        // sum of the members' weights
    int massless;    // the set has no mass: every member weighs 1
    Vec3<R> vector;  // the force on the centre, or the torque on the set
    R scale;         // torques: 1 / sum_j w_j |u_j|^2 (0 where there is no torque to apply)
};

template <class R>
struct SetRow {
    R energy;
    Vec3<R> separation;  // two sets: the second centre seen from the first
};

template <class R>
SMD_HD SMD_INLINE R set_member_weight(const Real4<R>* vel, int id, int massless) {
    return massless ? R(1) : vel[id].w;
}

// The centres of a row's S sets as its potential sees them: the first wrapped into the box, the others
// their minimum images seen from it.
template <int S, class R>
SMD_HD SMD_INLINE void set_row_centres(const Box<R>& box, const SetCentre<R>* row, Vec3<R>* c) {
    c[0] = box.wrap(row[0].centre);
    for (int s = 1; s < S; ++s) c[s] = c[0] + box.wrap(row[s].centre - row[0].centre);
}

// One thread per row: the centres of its sets and the potential's force or torque on each.
template <class Potential, class R>
struct SetCentresKernel {
    static constexpr int S = Potential::arity;
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    const Real4<R>* vel;  // w: mass
    Box<R> box;
    const int* members;
    const int* start;
    const Params* params;
    SetCentre<R>* centres;
    SetRow<R>* rows;

    SMD_HD void operator()(int64_t row) const {
        Vec3<R> c[S];
        for (int s = 0; s < S; ++s) {
            const int64_t k = row * S + s;
            const Vec3<R> first = xyz(pos[members[start[k]]]);
            Vec3<R> weighted{0, 0, 0}, plain{0, 0, 0};
            R mass = 0;
            for (int m = start[k]; m < start[k + 1]; ++m) {
                const Vec3<R> x = first + box.minimum_image(xyz(pos[members[m]]) - first);
                const R w = vel[members[m]].w;
                weighted += w * x;
                plain += x;
                mass += w;
            }
            SetCentre<R>& centre = centres[k];
            centre.massless = mass > R(0) ? 0 : 1;
            centre.weight = centre.massless ? R(start[k + 1] - start[k]) : mass;
            centre.centre = (R(1) / centre.weight) * (centre.massless ? plain : weighted);
        }
        set_row_centres<S>(box, centres + row * S, c);
        rows[row].separation = S > 1 ? c[S - 1] - c[0] : Vec3<R>{0, 0, 0};
        if constexpr (is_set_torque<Potential>::value) {
            Vec3<R> T[S];
            Potential::torques(c, params[row], box, T);
            for (int s = 0; s < S; ++s) {
                const int64_t k = row * S + s;
                SetCentre<R>& centre = centres[k];
                const Vec3<R> first = xyz(pos[members[start[k]]]);
                const R t2 = dot(T[s], T[s]);
                R inertia = 0;
                for (int m = start[k]; m < start[k + 1]; ++m) {
                    const Vec3<R> d = first + box.minimum_image(xyz(pos[members[m]]) - first) - centre.centre;
                    const Vec3<R> u = t2 > R(0) ? d - (dot(d, T[s]) / t2) * T[s] : d;
                    inertia += set_member_weight(vel, members[m], centre.massless) * dot(u, u);
                }
                centre.vector = T[s];
                // No torque, or every member on the axis: nothing to turn.
                centre.scale = t2 > R(0) && inertia > R(0) ? R(1) / inertia : R(0);
            }
            rows[row].energy = R(0);
        } else {
            Vec3<R> force[S];
            rows[row].energy = Potential::compute(c, params[row], box, force);
            for (int s = 0; s < S; ++s) {
                centres[row * S + s].vector = force[s];
                centres[row * S + s].scale = R(0);
            }
        }
    }
};

// One thread per member of every set: its share of its set's force, or its force of the set's torque.
template <class Potential, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct SetMembersKernel {
    static constexpr int S = Potential::arity;
    const Real4<R>* pos;
    const Real4<R>* vel;
    Box<R> box;
    const int* members;
    const int* start;
    const int* setOf;  // the set (row * S + s) of each member slot
    const SetCentre<R>* centres;
    const SetRow<R>* rows;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t slot) const {
        const int k = setOf[slot];
        const int64_t row = k / S;
        const int id = members[slot];
        const SetCentre<R>& centre = centres[k];
        const R w = set_member_weight(vel, id, centre.massless);
        Vec3<R> f{0, 0, 0};
        R e = 0;
        Tensor3<R> virial = zero_tensor<R>();
        if constexpr (is_set_torque<Potential>::value) {
            const Vec3<R> first = xyz(pos[members[start[k]]]);
            const Vec3<R> d = first + box.minimum_image(xyz(pos[id]) - first) - centre.centre;
            const Vec3<R> T = centre.vector;
            const R t2 = dot(T, T);
            const Vec3<R> u = t2 > R(0) ? d - (dot(d, T) / t2) * T : d;
            f = (w * centre.scale) * bonded_geometry::cross(T, u);
            if (WantVirial) virial = outer(d, f);
        } else {
            const R share = w / centre.weight;
            f = share * centre.vector;
            if (WantEnergy) e = share * rows[row].energy / R(S);
            if (WantVirial && S > 1)
                virial = (share / R(S)) * outer(rows[row].separation, centres[row * S + S - 1].vector);
        }
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, id, f, e, virial);
    }
};

// The Hessian column of particle `seed` (hessian_kernels.hpp), one thread per member slot j of the
// seed's row: the centres are linear in the members' positions, so d2U/dx_seed dx_j =
// (w_seed / W_a)(w_j / W_b) d2U/dC_a dC_b for the seed in set a and j in set b, the last factor minus
// the derivative (in dual numbers) of the force on C_b as C_a moves. Run after SetCentresKernel.
template <class Potential, class R>
struct SetHessianKernel {
    static constexpr int S = Potential::arity;
    using Params = typename Potential::template Params<Dual<R>>;
    const Real4<R>* vel;
    Box<R> box;
    const int* members;
    const int* setOf;
    const int* setOfParticle;  // by particle: its set (row * S + s), -1 in none
    const SetCentre<R>* centres;
    const Params* params;
    int seed;
    Tensor3<R>* blocks;

    SMD_HD void operator()(int64_t slot) const {
        const int seedSet = setOfParticle[seed];
        const int k = setOf[slot];
        if (seedSet < 0 || seedSet / S != k / S) return;
        const int row = k / S;
        Vec3<R> c[S];
        set_row_centres<S>(box, centres + row * S, c);
        const Box<Dual<R>> dualBox = constant_dual(box);
        Tensor3<R> h = zero_tensor<R>();
        for (int axis = 0; axis < 3; ++axis) {
            Vec3<Dual<R>> cd[S];
            for (int s = 0; s < S; ++s) cd[s] = s == seedSet % S ? seeded_dual(c[s], axis) : constant_dual(c[s]);
            Vec3<Dual<R>> force[S];
            Potential::compute(cd, params[row], dualBox, force);
            subtract_force_derivative(h, axis, force[k % S]);
        }
        const SetCentre<R>& a = centres[seedSet];
        const SetCentre<R>& b = centres[k];
        const int id = members[slot];
        const R shares = set_member_weight(vel, seed, a.massless) / a.weight * set_member_weight(vel, id, b.massless) / b.weight;
        blocks[id] += shares * h;
    }
};

// An entry's sets and per-row parameters in backend memory, uploaded from the host: members and start
// as SetConfig's, setOf the set of each member slot (what a thread per member reads), params one per row.
template <class B, class Params>
struct SetBuffers {
    typename B::template Buffer<int> members, start, setOf;
    typename B::template Buffer<Params> params;

    SetBuffers(const B& backend, const std::vector<int>& hostMembers, const std::vector<int>& hostStart,
               const std::vector<Params>& hostParams) {
        std::vector<int> hostSetOf(hostMembers.size());
        for (size_t k = 0; k + 1 < hostStart.size(); ++k)
            for (int m = hostStart[k]; m < hostStart[k + 1]; ++m) hostSetOf[m] = static_cast<int>(k);
        backend.upload(members, hostMembers.data(), hostMembers.size());
        backend.upload(start, hostStart.data(), hostStart.size());
        backend.upload(setOf, hostSetOf.data(), hostSetOf.size());
        backend.upload(params, hostParams.data(), hostParams.size());
    }
};

template <class B, class R, class Potential>
class SetInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<R>;

    // members/start as SetConfig's, for the rows kept; params: one per row.
    SetInteraction(const B& backend, InteractorScope scope, const std::vector<int>& members,
                   const std::vector<int>& start, const std::vector<Params>& params)
        : Interactor<B, R>(std::move(scope)), backend_(backend), rowCount_(static_cast<int64_t>(params.size())),
          memberCount_(static_cast<int64_t>(members.size())), start_host_(start),
          sets_(backend, members, start, params) {
        backend_.resize(centres_, params.size() * Potential::arity);
        backend_.resize(rows_, params.size());
    }

    // Torques have no energy to differentiate; forces on centres get their exact second derivatives.
    void enable_hessian(int64_t particles, const std::vector<int>& members,
                        const std::vector<typename Potential::template Params<Dual<R>>>& params) {
        if constexpr (!is_set_torque<Potential>::value) {
            std::vector<int> setOfParticle(static_cast<size_t>(particles), -1);
            for (size_t k = 0; k + 1 < start_host_.size(); ++k)
                for (int m = start_host_[k]; m < start_host_[k + 1]; ++m) setOfParticle[members[m]] = static_cast<int>(k);
            backend_.upload(setOfParticle_, setOfParticle.data(), setOfParticle.size());
            backend_.upload(dualParams_, params.data(), params.size());
            hessian_ = true;
        }
    }
    bool has_hessian() const override { return hessian_; }
    void add_hessian(Particles<B, R>& particles, int seed, Tensor3<R>* blocks) override {
        if constexpr (!is_set_torque<Potential>::value) {
            if (rowCount_ == 0) return;
            backend_.for_each(rowCount_, centres_kernel(particles));
            backend_.for_each(memberCount_,
                              SetHessianKernel<Potential, R>{particles.vel.data(), particles.box, sets_.members.data(),
                                                             sets_.setOf.data(), setOfParticle_.data(), centres_.data(),
                                                             dualParams_.data(), seed, blocks});
        }
    }

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        if (rowCount_ == 0) return;
        ForceOutputs<R> own = out;
        if (Potential::arity == 1 && !is_set_torque<Potential>::value) own.virial = nullptr;  // a field: no virial
        dispatch_outputs(own, [&](auto force, auto energy, auto virial) {
            backend_.for_each(rowCount_, centres_kernel(particles));
            backend_.for_each(memberCount_,
                              SetMembersKernel<Potential, R, decltype(force)::value, decltype(energy)::value,
                                               decltype(virial)::value>{
                                  particles.pos.data(), particles.vel.data(), particles.box, sets_.members.data(),
                                  sets_.start.data(), sets_.setOf.data(), centres_.data(), rows_.data(), own});
        });
    }

private:
    SetCentresKernel<Potential, R> centres_kernel(Particles<B, R>& particles) {
        return {particles.pos.data(), particles.vel.data(), particles.box, sets_.members.data(), sets_.start.data(),
                sets_.params.data(), centres_.data(), rows_.data()};
    }

    const B& backend_;
    int64_t rowCount_, memberCount_;
    std::vector<int> start_host_;
    typename B::template Buffer<int> setOfParticle_;
    typename B::template Buffer<typename Potential::template Params<Dual<R>>> dualParams_;
    bool hessian_ = false;
    SetBuffers<B, Params> sets_;
    typename B::template Buffer<SetCentre<R>> centres_;
    typename B::template Buffer<SetRow<R>> rows_;
};

// A potential's entry parameters (given once in the entry's "parameters"), if it has any.
template <class P, class = void>
struct set_entry_parameters {
    static std::vector<Parameter> get() { return {}; }
};
template <class P>
struct set_entry_parameters<P, std::void_t<decltype(P::entry_parameters())>> {
    static std::vector<Parameter> get() { return P::entry_parameters(); }
};

// The configurable component of a Set potential: read by set_read.cpp, made here.
template <class Potential>
struct SetComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& external = static_cast<const ExternalSpec&>(s);
        const auto& config = static_cast<const SetConfig&>(*s.config);
        const std::vector<uint8_t>* inGroup = s.group >= 0 ? &build.spec.groups[s.group].members : nullptr;
        const int S = config.sets;
        const size_t width = static_cast<size_t>(width_of(config.schema));
        const size_t rows = (config.start.size() - 1) / S;
        std::vector<int> members, start{0};
        std::vector<typename Potential::template Params<R>> params;
        std::vector<typename Potential::template Params<Dual<R>>> dualParams;
        for (size_t row = 0; row < rows; ++row) {
            const int* first = config.members.data() + config.start[row * S];
            const int* last = config.members.data() + config.start[row * S + S];
            // A row acts only when all its particles are in the entry's group, as a bond does.
            if (inGroup && !std::all_of(first, last, [&](int id) { return (*inGroup)[id]; })) continue;
            for (int set = 0; set < S; ++set) {
                members.insert(members.end(), config.members.begin() + config.start[row * S + set],
                               config.members.begin() + config.start[row * S + set + 1]);
                start.push_back(static_cast<int>(members.size()));
            }
            ParameterValues values = external.values;
            ParameterValues rowValues;
            rowValues.assign(config.schema, config.values.data() + row * width);
            for (const auto& [name, numbers] : rowValues.all()) values.set(name, numbers);
            params.push_back(Potential::template make_params<R>(values, build.context.constants));
            if (build.context.hessian)
                dualParams.push_back(Potential::template make_params<Dual<R>>(values, build.context.constants));
        }
        auto interactor = std::make_unique<SetInteraction<B, R, Potential>>(build.backend, build.scope(s), members,
                                                                            start, params);
        if (build.context.hessian) interactor->enable_hessian(build.context.particles, members, dualParams);
        return interactor;
    }
};

}  // namespace structmd
