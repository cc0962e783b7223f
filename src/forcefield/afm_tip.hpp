#pragma once
// UAMMD-structured's ["AFM","SphericalTip"]: an atomic-force-microscope tip over a sample. Each row of
// the entry's table names the tip (idSet_i, one particle) and its sample (idSet_j); the tip is held by
// a spring to the chip, which moves along z at constant velocity, and repels (or attracts) the sample.
//
//   chip:   U = 1/2 [Kxy (dx^2 + dy^2) + K dz^2],   d = wrap(chip(step) - r_tip)       (on the tip)
//   sample: U = |eps| [A (s/g)^12 + B (s/g)^6],      g = |r_j - r_tip| - R_tip            (each j)
//
// R_tip the tip particle's radius; eps >= 0: A = 0, B = 1 (a soft wall); eps < 0: A = 1, B = -2 (a
// well of depth |eps| at g = s). The chip starts at startChipPosition and, from indentationStartStep
// on, moves along z at tipVelocity, for dt (step - indentationStartStep); from
// indentationBackwardStep on (0: never) it moves back at the same speed. dt is the input's time step
// (global.fundamental's, else the first scheduled integrator's), as UAMMD-structured takes the
// fundamental's. Energy: the chip spring's to the tip, each sample particle's own to it; virial: half
// of d_j (x) f_j to each of the pair, none for the chip (a field). Sample particles do not interact
// with each other through this term; no cutoff. Read by afm_read.cpp into a SetConfig (two sets per
// row: the tip, then the sample); one thread per member, the tip's thread summing the reactions of its
// sample, so no particle is written twice (the reader refuses a particle in two sets).
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/set_interaction.hpp"
#include "state/step_clock.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from an AFM entry: the rows' sets and values, and the time step that moves
// the chip.
struct AfmConfig : SetConfig {
    double timeStep = 0.0;
};

struct SphericalTipPotential {
    template <class R>
    struct Params {
        R epsilon;  // |eps|
        R sigma;
        R A, B;
    };

    static std::vector<Parameter> parameters() { return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)}; }
    template <class R>
    static Params<R> make_params(const ParameterValues& v) {
        const double eps = v["epsilon"];
        return eps < 0.0 ? Params<R>{R(-eps), R(v["sigma"]), R(1), R(-2)} : Params<R>{R(eps), R(v["sigma"]), R(0), R(1)};
    }

    // The energy of a sample particle at d = r_j - r_tip from the tip, and the force on it.
    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> d, R tipRadius, const Params<R>& p, Vec3<R>& force) {
        const R r = sqrt(dot(d, d));
        const R g = r - tipRadius;
        const R s2 = p.sigma * p.sigma / (g * g);
        const R s6 = s2 * s2 * s2;
        // dU/dg = -|eps| (12 A s^12 + 6 B s^6) / g; g grows along d / r.
        const R dUdg = -p.epsilon * (R(12) * p.A * s6 * s6 + R(6) * p.B * s6) / g;
        force = r > R(0) ? (-dUdg / r) * d : Vec3<R>{R(0), R(0), R(0)};
        return p.epsilon * (p.A * s6 * s6 + p.B * s6);
    }
};

template <class Tip, class R>
struct AfmParams {
    typename Tip::template Params<R> tip;
    Vec3<R> K;     // (Kxy, Kxy, K)
    Vec3<R> chip;  // the chip's start
    R velocity;    // along z
    R timeStep;
    int64_t startStep, backwardStep;

    // The chip at `step`.
    SMD_HD SMD_INLINE Vec3<R> chip_at(int64_t step) const {
        Vec3<R> c = chip;
        if (step >= startStep && step < backwardStep) c.z += velocity * timeStep * R(step - startStep);
        if (step >= backwardStep)
            c.z += velocity * timeStep * R(backwardStep - startStep) - velocity * timeStep * R(step - backwardStep);
        return c;
    }
};

// The values of row `row` of an AFM entry (also read by ["ExperimentMeasures","AFMMeasure"]).
template <class Tip, class R>
AfmParams<Tip, R> afm_row_params(const AfmConfig& config, size_t row) {
    ParameterValues v;
    v.assign(config.schema, config.values.data() + row * static_cast<size_t>(width_of(config.schema)));
    const std::array<double, 3> chip = v.vec3("startChipPosition");
    const double backward = v["indentationBackwardStep"];
    return {Tip::template make_params<R>(v),
            {R(v["Kxy"]), R(v["Kxy"]), R(v["K"])},
            {R(chip[0]), R(chip[1]), R(chip[2])},
            R(v["tipVelocity"]),
            R(config.timeStep),
            static_cast<int64_t>(v["indentationStartStep"]),
            backward > 0.0 ? static_cast<int64_t>(backward) : INT64_MAX};
}

template <class Tip, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct AfmKernel {
    const Real4<R>* pos;
    const R* radius;
    Box<R> box;
    const int* members;  // per row: the tip, then its sample
    const int* start;    // set k = 2 row (the tip) or 2 row + 1 (the sample): members[start[k] .. start[k + 1])
    const int* setOf;
    const AfmParams<Tip, R>* params;
    ClockView clock;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t slot) const {
        const int k = setOf[slot];
        const int row = k / 2;
        const int tip = members[start[2 * row]];
        const int id = members[slot];
        const AfmParams<Tip, R>& p = params[row];
        const Vec3<R> tipPos = xyz(pos[tip]);
        const R tipRadius = radius[tip];
        Vec3<R> f{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        if (k % 2 == 1) {
            const Vec3<R> d = box.minimum_image(xyz(pos[id]) - tipPos);
            const R energy = Tip::compute(d, tipRadius, p.tip, f);
            if (WantEnergy) e = energy;
            if (WantVirial) w = R(0.5) * outer(d, f);
        } else {
            const Vec3<R> d = box.wrap(p.chip_at(clock.step()) - tipPos);
            f = {p.K.x * d.x, p.K.y * d.y, p.K.z * d.z};
            if (WantEnergy) e = R(0.5) * (p.K.x * d.x * d.x + p.K.y * d.y * d.y + p.K.z * d.z * d.z);
            for (int m = start[2 * row + 1]; m < start[2 * row + 2]; ++m) {
                const Vec3<R> dj = box.minimum_image(xyz(pos[members[m]]) - tipPos);
                Vec3<R> fj;
                Tip::compute(dj, tipRadius, p.tip, fj);
                f -= fj;
                if (WantVirial) w += R(0.5) * outer(dj, fj);
            }
        }
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, id, f, e, w);
    }
};

template <class B, class R, class Tip>
class AfmInteraction : public Interactor<B, R> {
public:
    AfmInteraction(const B& backend, InteractorScope scope, const std::vector<int>& members,
                   const std::vector<int>& start, const std::vector<AfmParams<Tip, R>>& params)
        : Interactor<B, R>(std::move(scope)), backend_(backend), memberCount_(static_cast<int64_t>(members.size())),
          sets_(backend, members, start, params) {}

    void compute(Particles<B, R>& particles, const ForceOutputs<R>& out) override {
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            backend_.for_each(memberCount_,
                              AfmKernel<Tip, R, decltype(force)::value, decltype(energy)::value, decltype(virial)::value>{
                                  particles.pos.data(), particles.radius.data(), particles.box, sets_.members.data(),
                                  sets_.start.data(), sets_.setOf.data(), sets_.params.data(), particles.now(), out});
        });
    }

private:
    const B& backend_;
    int64_t memberCount_;
    SetBuffers<B, AfmParams<Tip, R>> sets_;
};

template <class Tip>
struct AfmComponent {
    static ForceFieldComponent reader_entry(ComponentKey key);

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& config = static_cast<const AfmConfig&>(*s.config);
        const size_t rows = (config.start.size() - 1) / 2;
        const std::vector<uint8_t>* inGroup = s.group >= 0 ? &build.spec.groups[s.group].members : nullptr;
        std::vector<int> members, start{0};
        std::vector<AfmParams<Tip, R>> params;
        for (size_t row = 0; row < rows; ++row) {
            const auto first = config.members.begin() + config.start[2 * row];
            const auto last = config.members.begin() + config.start[2 * row + 2];
            // A row acts only when its tip and whole sample are in the entry's group.
            if (inGroup && !std::all_of(first, last, [&](int id) { return (*inGroup)[id]; })) continue;
            members.insert(members.end(), first, last);
            start.push_back(start.back() + 1);
            start.push_back(static_cast<int>(members.size()));
            params.push_back(afm_row_params<Tip, R>(config, row));
        }
        return std::make_unique<AfmInteraction<B, R, Tip>>(build.backend, build.scope(s), members, start, params);
    }
};

}  // namespace structmd
