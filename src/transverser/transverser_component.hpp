#pragma once
// A transverser registered by name (by a plugin, engines/plugin.hpp) that a host runs once over the
// current state and reads back per particle (structmd_traverse). It is written against the contract
// of transverser.hpp, plus what the engine needs to make it and to size its output:
//
//   struct NeighbourCount {
//       static constexpr int values = 1;                    // numbers it writes per particle
//       static std::vector<Parameter> parameters();         // its named parameters (may be empty)
//       template <class R> struct Functor { ... };          // the transverser.hpp contract
//       template <class R>
//       static Functor<R> make(const TransverserInputs<R>& in, const ParameterValues& v);
//   };
//
// make() is called on the host before each run, with the particles' arrays on the backend and the
// output: Functor<R>::set(i, total) writes particle i's `values` numbers at in.out[values * i ...],
// all of them (the engine zeroes the output only for a group: particles outside it keep 0). The host
// receives them in id order.
// run_transverser, instantiated where the plugin is compiled (for CUDA by nvcc), launches the
// functor over a neighbour list or over all pairs, as the engine asks.
#include <functional>
#include <string>
#include <vector>

#include "core/box.hpp"
#include "core/parameters.hpp"
#include "core/vec.hpp"
#include "neighbour/neighbour_view.hpp"
#include "transverser/all_pairs_traversal.hpp"
#include "transverser/neighbour_traversal.hpp"

namespace structmd {

// What a transverser is made from: arrays on the backend, by particle index (= id), each null when the
// state does not have it.
template <class R>
struct TransverserInputs {
    int64_t count;
    const Real4<R>* positions;   // w: the type index
    const Real4<R>* velocities;  // w: the mass
    const R* charge;
    const R* radius;
    R* out;  // values * count numbers, zeroed only for a group (set writes every particle's otherwise)
};

// One run as the engine hands it to a registered transverser.
template <class B, class R>
struct TransverserRun {
    const B& backend;
    TransverserInputs<R> inputs;
    const NeighbourView<R>* neighbours;  // the list of the cutoff, up to date; null: all pairs
    R cutoff2;
    Box<R> box;
    const uint8_t* group;  // by particle; null: every particle
    const int* batch;      // the particles' batches numbered 0, 1, ...; null: one batch
};

// The reader's side of a registered transverser: what the host may pass it and what it writes.
struct TransverserEntry {
    std::string name;
    std::vector<Parameter> parameters;
    int values = 1;
};

// The engine's side, for one backend and precision.
template <class B, class R>
struct TransverserRunner {
    std::string name;
    std::function<void(const TransverserRun<B, R>&, const ParameterValues&)> run;
};

template <class T, class B, class R>
void run_transverser(const TransverserRun<B, R>& run, const ParameterValues& values) {
    using Functor = typename T::template Functor<R>;
    const Functor functor = T::template make<R>(run.inputs, values);
    const int64_t n = run.inputs.count;
    if (run.neighbours)
        run.backend.for_each_lanes(n, NeighbourTraversal<Functor, R>{functor, *run.neighbours, run.cutoff2, run.group});
    else
        traverse_all_pairs(run.backend, n,
                           AllPairsTraversal<Functor, R>{functor, run.inputs.positions, n, run.box, run.group, run.batch});
}

}  // namespace structmd
