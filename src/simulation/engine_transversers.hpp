#pragma once
// Engine's transversers: expression transversers (SimulationProbes::expression_sum), each prepared at
// its first run (its list, its compiled kernel) and kept by key; and registered transversers
// (SimulationProbes::traverse, traverse_on_backend), run by the plugin's runner for this backend and
// precision into one output array, which traverse copies to the host and traverse_on_backend lends.
#include <algorithm>
#include <string>
#include <vector>

#include "simulation/engine.hpp"
#include "transverser/transverser_component.hpp"

namespace structmd {

// A pair term's list where one offers every pair within the cutoff: the steps keep it up to date, so
// a transverser run after a step refreshes and builds nothing, and the end of every step call adapts
// it to what its builds needed (a copy to the host). Else a list of the transversers' own, made at the
// first call with that cutoff, which each run adapts (an overflowed particle meanwhile scans its
// cells, neighbour_view.hpp).
template <class B, class R, class PairR>
typename Engine<B, R, PairR>::TransverserList Engine<B, R, PairR>::transverser_list(double cutoff) {
    if (auto shared = forceField_.list_offering_every_pair_within(cutoff, context_.batch)) return {shared, false};
    const auto found = std::find_if(transverserLists_.begin(), transverserLists_.end(),
                                    [&](const auto& l) { return l.first == cutoff; });
    if (found != transverserLists_.end()) return {found->second, true};
    auto own = std::make_shared<VerletList<B, R>>(backend_, cutoff, 1.1, PairCondition::all, PairFilterInputs{},
                                                  context_.batch, context_.batches, context_.model);
    transverserLists_.emplace_back(cutoff, own);
    return {own, true};
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::expression_sum(const ExpressionTransverserSpec& spec, double* perParticle) {
    backend_.activate();
    refresh_ghosts();
    const std::string key = spec.key();
    auto found = std::find_if(transversers_.begin(), transversers_.end(), [&](const auto& t) { return t.first == key; });
    if (found == transversers_.end()) {
        transversers_.emplace_back(key, std::make_unique<PreparedExpressionSum<B, R>>(backend_, spec, context_));
        found = transversers_.end() - 1;
    }
    PreparedExpressionSum<B, R>& prepared = *found->second;
    const TransverserList list = spec.cutoff > 0 ? transverser_list(spec.cutoff) : TransverserList{};
    prepared.run(p_, spec.group >= 0 ? forceField_.group(spec.group) : nullptr, list.list.get(), list.own);
    const std::vector<R> values = io_.download(prepared.output());
    std::copy(values.begin(), values.end(), perParticle);
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::traverse(const TransverserCall& call, double* perParticle) {
    run_registered_transverser(call);
    const std::vector<R> values = io_.download(transverserOut_);
    std::copy(values.begin(), values.end(), perParticle);
}

template <class B, class R, class PairR>
SimulationProbes::TransverserOutput Engine<B, R, PairR>::traverse_on_backend(const TransverserCall& call) {
    run_registered_transverser(call);
    backend_.synchronize();
    return {transverserOut_.data(), p_.count, call.values, static_cast<int>(sizeof(R)), backend_.device_ordinal()};
}

template <class B, class R, class PairR>
void Engine<B, R, PairR>::run_registered_transverser(const TransverserCall& call) {
    const TransverserRunner<B, R>* runner = call.source->template transverser_runner<B, R, PairR>(call.name);
    if (!runner)
        throw Error(STRUCTMD_ERR_UNSUPPORTED,
                    "transverser '" + call.name + "' (from plugin '" + call.source->source + "') has no implementation "
                    "for the " + B::name + " backend in this precision: that plugin was not compiled for it" +
                    (std::string(B::name) == "cuda" ? " (build it with CUDA, from a .cu source)" : ""));
    const uint8_t* group = nullptr;
    if (call.group != "All") {
        const auto named = std::find(groupNames_.begin(), groupNames_.end(), call.group);
        if (named == groupNames_.end())
            throw input_error(call.path, "no group named '" + call.group + "' (define it in a [\"Groups\", \"GroupsList\"] entry)");
        group = forceField_.group(static_cast<int>(named - groupNames_.begin()));
    }
    backend_.activate();
    refresh_ghosts();
    const TransverserList listed = call.cutoff > 0 ? transverser_list(call.cutoff) : TransverserList{};
    VerletList<B, R>* list = listed.list.get();
    const int64_t n = p_.count;
    backend_.resize(transverserOut_, n * call.values);
    // Without a group every particle's set writes its values (docs/plugins.md), so only a group
    // needs the zeros.
    if (group) backend_.fill(transverserOut_, R(0));
    if (n > 0) {
        const TransverserInputs<R> inputs{n, p_.pos.data(), p_.vel.empty() ? nullptr : p_.vel.data(),
                                          p_.charge.empty() ? nullptr : p_.charge.data(),
                                          p_.radius.empty() ? nullptr : p_.radius.data(), transverserOut_.data()};
        NeighbourView<R> view{};
        if (list) {
            list->update(p_.pos, n, p_.box, p_.version);
            view = list->view();
        }
        runner->run(TransverserRun<B, R>{backend_, inputs, list ? &view : nullptr, R(call.cutoff * call.cutoff), p_.box,
                                         group, context_.batch},
                    call.parameters);
        if (listed.own) list->adapt();
    }
}

}  // namespace structmd
