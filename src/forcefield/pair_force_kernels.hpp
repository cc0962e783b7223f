#pragma once
// The forces the other particles exert on one chosen particle s ("the seed"), term by term: a pair
// term's force between s and each neighbour, and each bond's forces split into central pair forces.
// A two-particle bond's force on one particle is all the other's (a direction-dependent spring's
// too). A bond of three or four particles whose energy depends on their relative positions only has forces
// F_a = sum_b c_ab (r_a - r_b) (c_ab = c_ba), unique where the geometry is not degenerate; the c_ab
// are found from the bond's own forces by least squares, so every bond functor splits without a
// formula of its own. The force b exerts on a is then c_ab (r_a - r_b).
#include "core/box.hpp"
#include "core/hd.hpp"
#include "core/real_limits.hpp"
#include "core/vec.hpp"
#include "forcefield/pair_kernel.hpp"
#include "forcefield/seed_traversal.hpp"

namespace structmd {

// c[p] for the pairs p = (a, b), a < b, in the order (0,1), (0,2), ..., (N-2,N-1): the least-squares
// solution of F_a = sum_b c_ab (r_a - r_b). Normal equations A c = y with A_pq = (u_p . u_q) times
// the overlap of the pairs' signs and y_p = u_p . (F_a - F_b), u_p = r_a - r_b. A is symmetric and
// positive semi-definite; a ridge of 100 eps times its largest diagonal element makes it definite,
// so elimination needs no pivoting, and where the split is not unique (collinear or coplanar
// particles) it takes the smallest c.
template <int N, class R>
SMD_HD SMD_INLINE void central_force_split(const Vec3<R>* r, const Vec3<R>* force, R* c) {
    constexpr int P = N * (N - 1) / 2;
    int first[P], second[P];
    Vec3<R> u[P];
    for (int a = 0, p = 0; a < N; ++a)
        for (int b = a + 1; b < N; ++b, ++p) {
            first[p] = a;
            second[p] = b;
            u[p] = r[a] - r[b];
        }
    R A[P][P];
    R largest = R(0);
    for (int p = 0; p < P; ++p) {
        for (int q = 0; q < P; ++q) {
            const int overlap = (first[p] == first[q]) + (second[p] == second[q]) - (first[p] == second[q]) -
                                (second[p] == first[q]);
            A[p][q] = R(overlap) * dot(u[p], u[q]);
        }
        c[p] = dot(u[p], force[first[p]] - force[second[p]]);
        largest = A[p][p] > largest ? A[p][p] : largest;
    }
    const R ridge = R(100) * machine_epsilon<R>() * largest;
    for (int p = 0; p < P; ++p) A[p][p] += ridge;
    for (int col = 0; col < P; ++col)
        for (int row = col + 1; row < P; ++row) {
            const R factor = A[row][col] / A[col][col];
            for (int k = col; k < P; ++k) A[row][k] -= factor * A[col][k];
            c[row] -= factor * c[col];
        }
    for (int row = P - 1; row >= 0; --row) {
        for (int k = row + 1; k < P; ++k) c[row] -= A[row][k] * c[k];
        c[row] /= A[row][row];
    }
}

// A radial pair term: neighbour j exerts (U'(r)/r) (r_j - r_s) on the seed.
template <class Potential, class R, class PairR>
struct PairForceOnSeedKernel {
    using Params = typename Potential::template Params<PairR>;
    const R* charge;
    const R* radius;
    const uint8_t* group;
    NeighbourView<R> neighbours;
    PairTable<Params> table;
    int seed;
    Real4<R>* out;

    SMD_HD void operator()(int64_t k) const {
        for_each_partner_of_seed<PairR>(neighbours, k, seed, group, table,
                                        [&](int j, const Vec3<R>& d, const Params& p) {
            const PairTerm<PairR> t = evaluate_pair_of<Potential>(PairR(dot(d, d)), p, charge, radius, seed, j);
            const Vec3<R> f = R(t.dudr_over_r) * d;
            accumulate(out[j], f);
        });
    }
};

// A bonded term of N >= 2 particles: for particle i in a bond with the seed, the force that i exerts
// on the seed in that bond: the bond's whole force on the seed for N = 2, its central split for more.
template <class Potential, class R>
struct BondForceOnSeedKernel {
    static constexpr int N = Potential::arity;
    using Params = typename Potential::template Params<R>;
    BondsAroundSeed<N, R, Params> bonds;
    Real4<R>* out;

    SMD_HD void operator()(int64_t i) const {
        if (i == bonds.seed) return;
        Vec3<R> total{R(0), R(0), R(0)};
        bonds.for_each_of(i, [&](const Params& params, int slot, int seedSlot, const Vec3<R>* r) {
            Vec3<R> force[N];
            Potential::compute(r, params, bonds.box, force);
            if constexpr (N == 2) {
                total += force[seedSlot];  // all of it comes from the other particle, central or not
            } else {
                R c[N * (N - 1) / 2];
                central_force_split<N>(r, force, c);
                const int a = seedSlot < slot ? seedSlot : slot, z = seedSlot < slot ? slot : seedSlot;
                total += c[a * N - a * (a + 1) / 2 + (z - a - 1)] * (r[seedSlot] - r[slot]);
            }
        });
        accumulate(out[i], total);
    }
};

}  // namespace structmd
