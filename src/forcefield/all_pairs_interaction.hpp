#pragma once
// A non-bonded pair term over all pairs (an ["NBody", "all"] list entry, UAMMD's NBody module): each
// particle of the term's group visits every other one of its batch, at the nearest image, through the
// same potential functor as the Verlet-list path (pair_interaction.hpp), as a transverser
// (pair_term_transverser.hpp) run by AllPairsTraversal. n^2 pairs: for terms of no finite range in an
// open box (Coulomb, Gravity) and for systems too small for a list to pay.
#include <memory>
#include <vector>

#include "forcefield/interactor.hpp"
#include "forcefield/lambda_coupling.hpp"
#include "forcefield/pair_term_transverser.hpp"
#include "transverser/all_pairs_traversal.hpp"

namespace structmd {

template <class Potential, class = void>
struct uses_masses : std::false_type {};
template <class Potential>
struct uses_masses<Potential, std::void_t<decltype(Potential::uses_masses)>>
    : std::bool_constant<Potential::uses_masses> {};

// A potential of the masses' products (Gravity) as the kernels see it: they multiply the per-particle
// column they are given pairwise and hand the product to evaluate(r2, p, product), as for charges.
template <class Potential>
struct OfMassProducts : Potential {
    static constexpr bool uses_charges = true;
};

// Copies each particle's mass (the w of its velocity) into a column of its own for the pair products.
template <class R>
struct CopyMasses {
    const Real4<R>* vel;
    R* mass;
    SMD_HD void operator()(int64_t i) const { mass[i] = vel[i].w; }
};

template <class B, class R, class Potential, class PairR = R>
class AllPairsInteraction : public Interactor<B, R> {
public:
    using Params = typename Potential::template Params<PairR>;
    using Evaluated = std::conditional_t<uses_masses<Potential>::value, OfMassProducts<Potential>, Potential>;

    // tableBatch: the particles' batches when the table has one block per batch, else null. batch: the
    // particles' batches (null: one batch), which never pair.
    AllPairsInteraction(const B& backend, InteractorScope scope, const std::vector<Params>& table, int ntypes,
                        const int* tableBatch, const int* batch)
        : Interactor<B, R>(std::move(scope)), backend_(backend), ntypes_(ntypes), tableBatch_(tableBatch), batch_(batch) {
        backend_.upload(table_, table.data(), table.size());
    }

    bool pairwise() const override { return true; }

    void prepare(Particles<B, R>& p) override {
        if constexpr (uses_masses<Potential>::value) {
            backend_.resize(masses_, p.count);
            backend_.for_each(p.count, CopyMasses<R>{p.vel.data(), masses_.data()});
        }
    }

    void compute(Particles<B, R>& p, const ForceOutputs<R>& out) override {
        dispatch_outputs(out, [&](auto force, auto energy, auto virial) {
            using Term = PairTermTransverser<Evaluated, R, PairR, decltype(force)::value, decltype(energy)::value,
                                             decltype(virial)::value>;
            traverse(p, Term{products(p), p.radius.data(), table(), out});
        });
    }

    bool couples_to_lambda() const override { return structmd::couples_to_lambda<Potential>::value; }
    void add_lambda_derivative(Particles<B, R>& p, R* perParticle) override {
        if constexpr (structmd::couples_to_lambda<Potential>::value) {
            using Term = PairTermTransverser<PairLambdaDerivative<Potential>, R, PairR, false, true, false>;
            traverse(p, Term{products(p), p.radius.data(), table(), energy_outputs(perParticle)});
        }
    }

private:
    template <class Term>
    void traverse(Particles<B, R>& p, const Term& term) {
        traverse_all_pairs(backend_, p.count,
                           AllPairsTraversal<Term, R>{term, p.pos.data(), p.count, p.box, this->group(), batch_});
    }
    // The column whose pairwise products the potential takes: the charges, or the masses.
    const R* products(Particles<B, R>& p) const {
        if constexpr (uses_masses<Potential>::value)
            return masses_.data();
        else
            return p.charge.data();
    }
    PairTable<Params> table() const { return PairTable<Params>{table_.data(), ntypes_, tableBatch_}; }

    const B& backend_;
    typename B::template Buffer<Params> table_;
    typename B::template Buffer<R> masses_;
    int ntypes_;
    const int* tableBatch_;
    const int* batch_;
};

}  // namespace structmd
