#pragma once
// Engine's expression transversers (SimulationProbes::expression_sum): each prepared at its first
// run (its list, its compiled kernel) and kept by key.
#include <algorithm>
#include <string>
#include <vector>

#include "simulation/engine.hpp"

namespace structmd {

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
    prepared.run(p_, spec.group >= 0 ? forceField_.group(spec.group) : nullptr);
    const std::vector<R> values = io_.download(prepared.output());
    std::copy(values.begin(), values.end(), perParticle);
}

}  // namespace structmd
