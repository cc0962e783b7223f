#pragma once
// ["PatchyParticles","PatchyParticles"] and ["PatchyParticles","DynamicallyBondedPatchyParticles"]:
// patches are virtual sites at fixed body-frame offsets of their parent particle, carried by its
// position and turned by its orientation (site = x_parent + R(q_parent) offset). The entry's own
// force field acts between patches (patchy_potentials.hpp) and on single patches; each patch's force
// F acts on its parent as F plus the torque (R(q) offset) x F, and orientation-dependent terms add
// their torque on the parent directly. A pair's energy (and virial) is split equally between the
// two patches, and a patch's share goes to its parent.
//
// The dynamically bonded variant lets each patch interact with one partner at most. Every patch keeps
// a bond (a partner patch or none) and, while the forces are computed, remembers the partner of its
// lowest pair energy below energyThreshold (its candidate). Once per configuration, before the terms
// are computed, two patches that were each other's candidate become bonded and every other patch is
// left unbonded; then a pair interacts only when both patches are unbonded or bonded to each other.
// The reader is patchy_read.cpp; the patches' neighbour list is a VerletList over the sites.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/quaternion.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/patchy_potentials.hpp"
#include "neighbour/verlet_list.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from a patchy entry (host side, double precision).
struct PatchyConfig : ComponentConfig {
    bool dynamic = false;
    double energyThreshold = 0.0;
    std::vector<std::string> typeNames;  // the patches' own types (patchesGlobal.types)
    std::vector<double> typeRadius;
    // By patch, in the order of patchesState: its parent particle, type and body-frame offset.
    std::vector<int> parent;
    std::vector<int> type;
    std::vector<Vec3<double>> offset;
    // The pair terms' neighbour list (none without pair terms).
    bool hasPairs = false;
    double cutoff = 0.0;
    double verletFactor = 1.1;
    PairCondition condition = PairCondition::all;
    // Each term at most once; a table entry by (type i, type j) or by type, with whether it is listed.
    std::vector<DistanceSwitchCosinePatch::Params<double>> cosine;
    std::vector<uint8_t> cosineListed;
    std::vector<CosrapPatch::Params<double>> cosrap;
    std::vector<uint8_t> cosrapListed;
    std::vector<LinkerPatch::Params<double>> linker;
    std::vector<uint8_t> linkerListed;

    int ntypes() const { return static_cast<int>(typeNames.size()); }
};

// The patches' bond state (dynamically bonded variant only), by patch.
struct PatchBonds {
    int* bond;          // the bonded partner patch, or -1
    int* candidate;     // the partner of the lowest pair energy seen at this configuration, or -1
    double* lowest;     // that energy (energyThreshold when none is below it)
    double threshold;
};

template <class R>
struct PlacePatches {
    const Real4<R>* pos;
    const Real4<R>* dir;  // null: every parent has the identity orientation
    const int* parent;
    const int* type;
    const Vec3<R>* offset;
    Box<R> box;
    Real4<R>* sites;  // wrapped, w: patch type (for the list)
    Vec3<R>* lever;   // from the parent to the patch, lab frame
    R* height;        // the site's z before wrapping (surface terms)

    SMD_HD void operator()(int64_t a) const {
        const int p = parent[a];
        const Real4<R> q = dir ? dir[p] : Real4<R>{R(1), R(0), R(0), R(0)};
        const Vec3<R> v = patch_math::apply(patch_math::frame_of(q), offset[a]);
        const Vec3<R> x = xyz(pos[p]) + v;
        const Vec3<R> w = box.wrap(x);
        sites[a] = Real4<R>{w.x, w.y, w.z, R(type[a])};
        lever[a] = v;
        height[a] = x.z;
    }
};

// Bonds patches that chose each other at the last configuration (reads every candidate; the reset
// of the candidates is a second pass, so no patch reads one already reset).
struct FormPatchBonds {
    PatchBonds bonds;
    SMD_HD void operator()(int64_t a) const {
        const int c = bonds.candidate[a];
        bonds.bond[a] = (bonds.lowest[a] < bonds.threshold && c >= 0 && bonds.candidate[c] == a) ? c : -1;
    }
};
struct ResetPatchCandidates {
    PatchBonds bonds;
    SMD_HD void operator()(int64_t a) const {
        bonds.candidate[a] = -1;
        bonds.lowest[a] = bonds.threshold;
    }
};

// The tables of the terms on the backend, in real R; a null table: the term is absent.
template <class R>
struct PatchTerms {
    const DistanceSwitchCosinePatch::Params<R>* cosine;
    const uint8_t* cosineListed;
    const CosrapPatch::Params<R>* cosrap;
    const uint8_t* cosrapListed;
    const LinkerPatch::Params<R>* linker;
    const uint8_t* linkerListed;
    int ntypes;
};

// Every term's force, torque (on the parent), energy and virial on one patch, stored (not added) into
// the per-patch buffers. With pair terms the kernel runs over the list's slots, else over patches.
template <class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct PatchKernel {
    bool hasPairs;
    NeighbourView<R> neighbours;
    const Real4<R>* dir;
    const int* parent;
    const int* type;
    const Vec3<R>* lever;
    const R* height;
    PatchTerms<R> terms;
    bool dynamic;
    PatchBonds bonds;
    Real4<R>* force;  // by patch: the force on the patch (xyz) ...
    Real4<R>* torque;  // ... and the torque on its parent
    R* energy;
    Tensor3<R>* virial;

    SMD_HD void operator()(int64_t k) const {
        const NeighbourView<R>& v = neighbours;
        const int a = hasPairs ? v.order[k] : static_cast<int>(k);
        const int ta = type[a];
        const Real4<R> qa = dir ? dir[parent[a]] : Real4<R>{R(1), R(0), R(0), R(0)};
        Vec3<R> f{R(0), R(0), R(0)}, t{R(0), R(0), R(0)};
        R e = R(0);
        Tensor3<R> w = zero_tensor<R>();
        if (hasPairs) {
            const Vec3<R> ra = xyz(v.positions[k]);
            const int bondA = dynamic ? bonds.bond[a] : -1;
            R lowest = dynamic ? R(bonds.lowest[a]) : R(0);
            int candidate = -1;
            v.for_each_neighbour(static_cast<int>(k), [&](int s) {
                const int b = v.order[s];
                if (dynamic) {
                    const int bondB = bonds.bond[b];
                    if (!((bondA < 0 && bondB < 0) || (bondA == b && bondB == a))) return;
                }
                const Vec3<R> rab = v.box.minimum_image(xyz(v.positions[s]) - ra);
                const int entry = ta * terms.ntypes + type[b];
                const Real4<R> qb = dir ? dir[parent[b]] : Real4<R>{R(1), R(0), R(0), R(0)};
                const auto add = [&](const PatchPairTerm<R>& term) {
                    f += term.force;
                    t += term.torque;
                    e += R(0.5) * term.energy;
                    if (WantVirial) w += R(-0.5) * outer(rab, term.force);
                    if (dynamic && term.energy < lowest) {
                        lowest = term.energy;
                        candidate = b;
                    }
                };
                if (terms.cosine && terms.cosineListed[entry])
                    add(DistanceSwitchCosinePatch::evaluate(rab, qa, qb, terms.cosine[entry]));
                if (terms.cosrap && terms.cosrapListed[entry])
                    add(CosrapPatch::evaluate(rab, qa, qb, terms.cosrap[entry]));
            });
            if (dynamic && candidate >= 0) {
                bonds.lowest[a] = double(lowest);
                bonds.candidate[a] = candidate;
            }
        }
        // The pair forces act on the patch; the surface's force is added to them, as both turn the
        // parent through the same lever.
        if (terms.linker && terms.linkerListed[ta]) {
            R fz;
            e += LinkerPatch::evaluate(height[a], terms.linker[ta], fz);
            f.z += fz;
        }
        if (WantForce) {
            force[a] = Real4<R>{f.x, f.y, f.z, R(0)};
            const Vec3<R> tau = patch_math::cross(lever[a], f) + t;
            torque[a] = Real4<R>{tau.x, tau.y, tau.z, R(0)};
        }
        if (WantEnergy) energy[a] = e;
        if (WantVirial) virial[a] = w;
    }
};

// Adds each particle's patches' sums to the outputs (patches of particle i: members[start[i] ..
// start[i + 1])); one thread per particle.
template <class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct GatherPatches {
    const int* start;
    const int* members;
    const Real4<R>* force;
    const Real4<R>* torque;
    const R* energy;
    const Tensor3<R>* virial;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        if (start[i] == start[i + 1]) return;
        Vec3<R> f{R(0), R(0), R(0)}, t{R(0), R(0), R(0)};
        R e = R(0);
        Tensor3<R> w = zero_tensor<R>();
        for (int m = start[i]; m < start[i + 1]; ++m) {
            const int a = members[m];
            if (WantForce) {
                f += xyz(force[a]);
                t += xyz(torque[a]);
            }
            if (WantEnergy) e += energy[a];
            if (WantVirial) w += virial[a];
        }
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w, t);
    }
};

template <class B, class R>
class PatchyInteraction : public Interactor<B, R> {
public:
    template <class T>
    using Buffer = typename B::template Buffer<T>;

    PatchyInteraction(const InteractorBuild<B, R>& build, InteractorScope scope, const PatchyConfig& config)
        : Interactor<B, R>(std::move(scope)),
          backend_(build.backend),
          patches_(static_cast<int64_t>(config.parent.size())),
          hasPairs_(config.hasPairs),
          dynamic_(config.dynamic),
          threshold_(config.energyThreshold) {
        const B& backend = build.backend;
        backend.upload(parent_, config.parent.data(), config.parent.size());
        backend.upload(type_, config.type.data(), config.type.size());
        std::vector<Vec3<R>> offset;
        for (const Vec3<double>& o : config.offset) offset.push_back({R(o.x), R(o.y), R(o.z)});
        backend.upload(offset_, offset.data(), offset.size());
        // The patches of each particle, by particle id.
        const int64_t n = build.context.particles;
        std::vector<int> start(n + 1, 0), members(config.parent.size());
        for (int p : config.parent) ++start[p + 1];
        for (int64_t i = 0; i < n; ++i) start[i + 1] += start[i];
        std::vector<int> next(start.begin(), start.end() - 1);
        for (size_t a = 0; a < config.parent.size(); ++a) members[next[config.parent[a]]++] = static_cast<int>(a);
        backend.upload(start_, start.data(), start.size());
        backend.upload(members_, members.data(), members.size());
        for (auto* buffer : {&sites_, &force_, &torque_}) backend.resize(*buffer, patches_);
        backend.resize(lever_, patches_);
        backend.resize(height_, patches_);
        backend.resize(energy_, patches_);
        upload_table(cosine_, config.cosine);
        upload_table(cosrap_, config.cosrap);
        upload_table(linker_, config.linker);
        backend.upload(cosineListed_, config.cosineListed.data(), config.cosineListed.size());
        backend.upload(cosrapListed_, config.cosrapListed.data(), config.cosrapListed.size());
        backend.upload(linkerListed_, config.linkerListed.data(), config.linkerListed.size());
        ntypes_ = config.ntypes();
        if (hasPairs_) {
            PairFilterInputs inputs;
            if (config.condition == PairCondition::interDifferentType) inputs.kind = config.type;
            list_ = std::make_shared<VerletList<B, R>>(backend, config.cutoff, config.verletFactor, config.condition,
                                                      inputs, nullptr, 1, parent_.data());
            build.forceField.add_site_list(list_);
        }
        if (dynamic_) {
            backend.resize(bond_, patches_);
            backend.resize(candidate_, patches_);
            backend.resize(lowest_, patches_);
            backend.fill(bond_, -1);
            backend.fill(candidate_, -1);
            backend.fill(lowest_, threshold_);
        }
    }

    // The sites follow the parents; a new configuration first settles the bonds its predecessor chose.
    void prepare(Particles<B, R>& p) override {
        if (p.version == preparedAt_) return;
        preparedAt_ = p.version;
        backend_.for_each(patches_, PlacePatches<R>{p.pos.data(), p.dir.empty() ? nullptr : p.dir.data(),
                                                    parent_.data(), type_.data(), offset_.data(), p.box,
                                                    sites_.data(), lever_.data(), height_.data()});
        if (hasPairs_) list_->update(sites_, patches_, p.box, ++siteVersion_);
        if (dynamic_) {
            backend_.for_each(patches_, FormPatchBonds{bonds()});
            backend_.for_each(patches_, ResetPatchCandidates{bonds()});
        }
    }

    void compute(Particles<B, R>& p, const ForceOutputs<R>& out) override {
        if (out.virial && virial_.size() == 0) backend_.resize(virial_, patches_);
        const PatchTerms<R> terms{table(cosine_), cosineListed_.data(), table(cosrap_), cosrapListed_.data(),
                                  table(linker_), linkerListed_.data(), ntypes_};
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            constexpr bool F = decltype(force)::value, E = decltype(energy)::value, V = decltype(virial)::value;
            NeighbourView<R> view;
            if (hasPairs_) view = list_->view();
            backend_.for_each(patches_, PatchKernel<R, F, E, V>{hasPairs_, view, p.dir.empty() ? nullptr : p.dir.data(),
                                                                parent_.data(), type_.data(), lever_.data(),
                                                                height_.data(), terms, dynamic_, bonds(), force_.data(),
                                                                torque_.data(), energy_.data(), virial_.data()});
            backend_.for_each(p.count, GatherPatches<R, F, E, V>{start_.data(), members_.data(), force_.data(),
                                                                 torque_.data(), energy_.data(), virial_.data(), out});
        });
    }

    bool dynamic() const { return dynamic_; }
    // By patch, its bonded partner or -1 (dynamic entries only): the bonds the last evaluation used.
    const Buffer<int>& bonds_buffer() const { return bond_; }

private:
    PatchBonds bonds() {
        return PatchBonds{bond_.data(), candidate_.data(), lowest_.data(), threshold_};
    }
    template <class P, class H>
    void upload_table(Buffer<P>& buffer, const std::vector<H>& host) {
        std::vector<P> converted;
        for (const H& h : host) converted.push_back(convert(h));
        backend_.upload(buffer, converted.data(), converted.size());
    }
    static DistanceSwitchCosinePatch::Params<R> convert(const DistanceSwitchCosinePatch::Params<double>& h) {
        return {R(h.E), R(h.K), R(h.rc)};
    }
    static CosrapPatch::Params<R> convert(const CosrapPatch::Params<double>& h) {
        return {R(h.E), R(h.Kswt), R(h.Krap), R(h.rc),
                Real4<R>{R(h.rotation.x), R(h.rotation.y), R(h.rotation.z), R(h.rotation.w)}};
    }
    static LinkerPatch::Params<R> convert(const LinkerPatch::Params<double>& h) {
        return {R(h.epsilon), R(h.sigma), R(h.surface)};
    }
    template <class P>
    const P* table(const Buffer<P>& buffer) const {
        return buffer.size() == 0 ? nullptr : buffer.data();
    }

    const B& backend_;
    int64_t patches_;
    bool hasPairs_;
    bool dynamic_;
    double threshold_;
    int ntypes_ = 0;
    Buffer<int> parent_, type_, start_, members_;
    Buffer<Vec3<R>> offset_, lever_;
    Buffer<Real4<R>> sites_, force_, torque_;
    Buffer<R> height_, energy_;
    Buffer<Tensor3<R>> virial_;
    Buffer<DistanceSwitchCosinePatch::Params<R>> cosine_;
    Buffer<CosrapPatch::Params<R>> cosrap_;
    Buffer<LinkerPatch::Params<R>> linker_;
    Buffer<uint8_t> cosineListed_, cosrapListed_, linkerListed_;
    Buffer<int> bond_, candidate_;
    Buffer<double> lowest_;
    std::shared_ptr<VerletList<B, R>> list_;
    int64_t preparedAt_ = -1;
    int64_t siteVersion_ = 0;
};

// The two components: a configurable external (the patches and their force field are its entry).
struct PatchyParticlesComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);  // patchy_read.cpp

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        return std::make_unique<PatchyInteraction<B, R>>(build, build.scope(s), static_cast<const PatchyConfig&>(*s.config));
    }
};

}  // namespace structmd
