#pragma once
// The kernel of a non-bonded pair term over a Verlet list, generic in its potential. Each particle
// sums the forces of all its neighbours (a full list): no atomics, the same code on every backend,
// and a summation order fixed by the list. Energy and virial of a pair are split equally between
// the two. Free of the standard library, so that kernels compiled at run time (an expression
// potential on CUDA) instantiate this same traversal.
#include "core/hd.hpp"
#include "core/lanes.hpp"
#include "core/vec.hpp"
#include "forcefield/force_outputs.hpp"
#include "forcefield/pair_term.hpp"
#include "neighbour/neighbour_view.hpp"

#if SMD_HOST_CODE
#include "core/left_pack.hpp"

#include <cstring>
#include <type_traits>
#include <vector>
#endif

namespace structmd {

// Potentials of charges (Debye-Hueckel) declare `static constexpr bool uses_charges = true`, those of
// particle radii (Clashed, DLVO) `static constexpr bool uses_radii = true`.
template <class Potential>
SMD_HD constexpr auto uses_charges(int) -> decltype(bool(Potential::uses_charges)) {
    return Potential::uses_charges;
}
template <class Potential>
SMD_HD constexpr bool uses_charges(long) {
    return false;
}
template <class Potential>
SMD_HD constexpr auto uses_radii(int) -> decltype(bool(Potential::uses_radii)) {
    return Potential::uses_radii;
}
template <class Potential>
SMD_HD constexpr bool uses_radii(long) {
    return false;
}

// The potential is given what it declares it uses, in the order charge product, then radii.
template <class Potential, class R>
SMD_HD SMD_INLINE PairTerm<R> evaluate_pair(R r2, const typename Potential::template Params<R>& p, R chargeProduct,
                                            R radiusI, R radiusJ) {
    if constexpr (uses_charges<Potential>(0) && uses_radii<Potential>(0))
        return Potential::evaluate(r2, p, chargeProduct, radiusI, radiusJ);
    else if constexpr (uses_charges<Potential>(0))
        return Potential::evaluate(r2, p, chargeProduct);
    else if constexpr (uses_radii<Potential>(0))
        return Potential::evaluate(r2, p, radiusI, radiusJ);
    else
        return Potential::evaluate(r2, p);
}

// The parameters of a pair term by type pair: one ntypes x ntypes table, or one per batch
// (UAMMD-structured's batchId column) chosen by the first particle's batch, as batches never share
// a pair.
template <class Params>
struct PairTable {
    const Params* entries;  // ntypes x ntypes, or batches x ntypes x ntypes when `batch` is given
    int ntypes;
    const int* batch;  // by particle; null: one table for every batch

    SMD_HD SMD_INLINE const Params* row_of(int i, int type) const {
        return entries + (static_cast<int64_t>(batch ? batch[i] * ntypes : 0) + type) * ntypes;
    }
};

// The potential for particles i and j at r2, in the real T of r2 and p, given the per-particle data it
// declares: charges and radii are read only by the potentials that use them (no load otherwise).
template <class Potential, class T, class R>
SMD_HD SMD_INLINE PairTerm<T> evaluate_pair_of(T r2, const typename Potential::template Params<T>& p, const R* charge,
                                               const R* radius, int i, int j) {
    constexpr bool charges = uses_charges<Potential>(0), radii = uses_radii<Potential>(0);
    return evaluate_pair<Potential>(r2, p, charges ? T(charge[i] * charge[j]) : T(0), radii ? T(radius[i]) : T(0),
                                    radii ? T(radius[j]) : T(0));
}

#if SMD_HOST_CODE
template <class Potential, class R, class PairR>
struct PairRowsOnHost;  // below: PairKernel's loop on the CPU
#endif

// Sums in R; the potential itself in PairR. Separations in R, except where the potential is
// evaluated in float over positions in double (mixed precision) and the list keeps its positions
// relative to their cells in float (state/cell_local_positions.hpp): half the bytes gathered per
// neighbour, with a rounding of about 1e-7 of a cell's width whatever the size of the box. There
// each lane's force runs in float too, as OpenMM's mixed precision sums a thread's: a pair costs
// no conversion to double, the GPU's slowest arithmetic (16 a cycle per multiprocessor on the
// H100), and the lanes' sums, energies and virials stay in R.
// Runs over the list's slots (neighbour_view.hpp); what belongs to a particle (charge, group,
// radius, outputs) is looked up through the slot's particle.
template <class Potential, class R, class PairR, bool WantForce, bool WantEnergy, bool WantVirial>
struct PairKernel {
    using Params = typename Potential::template Params<PairR>;
    // A float potential over double positions (sizes, not types: no standard library here).
    static constexpr bool kCellLocal = sizeof(PairR) == sizeof(float) && sizeof(R) == sizeof(double);
    const R* charge;       // by particle, read only by potentials of charges
    const R* radius;       // by particle, read only by potentials of radii
    const uint8_t* group;  // by particle; null: every particle takes part
    NeighbourView<R> neighbours;
    PairTable<Params> table;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t k, Lanes lanes) const {
        if constexpr (kCellLocal) {
            if (neighbours.cellLocal.local) {
                over_cells(k, lanes);
                return;
            }
        }
        over_positions(k, lanes);
    }

#if SMD_HOST_CODE
    // Whether a launch may take the kernels of one type and no group (the template's kPlain below),
    // whose separations from the positions in R take the list's entries for slots.
    bool plain() const {
        const bool overCells = kCellLocal && neighbours.cellLocal.local;
        return table.ntypes == 1 && !group && (overCells || neighbours.entryShift == 0);
    }
#endif

    // Slot k's pairs with separations from the cell-local positions, the cells' offset taken from
    // the entry where the list's entries carry it. The double positions only for types: none read
    // where there is one type. kPlain: plain() holds (every kernel below).
    template <bool kPlain = false>
    SMD_HD SMD_INLINE void over_cells(int64_t k, Lanes lanes) const {
        const NeighbourView<R>& v = neighbours;
        const int i = v.order[k];
        if (!kPlain && group && !group[i]) return;
        const CellLocalPositions<R>& local = v.cellLocal;
        const Real4<float> li = local.local[k];
        const bool oneType = kPlain || table.ntypes == 1;
        const Params* row = table.row_of(i, oneType ? 0 : static_cast<int>(v.positions[k].w));
        const auto by_codes = [&](int s, int& typeJ) {
            typeJ = oneType ? 0 : static_cast<int>(v.positions[s].w);
            return local.separation(li, local.local[s]);
        };
        if (v.entryShift) {
            sum_pairs<float, kPlain>(k, i, row, lanes, [&](int entry, int& s, int& typeJ) {
                s = CellLocalPositions<R>::slot_of_entry(entry);
                typeJ = oneType ? 0 : static_cast<int>(v.positions[s].w);
                return local.separation(li, local.local[s], entry);
            }, by_codes);
        } else {
            sum_pairs<float, kPlain>(k, i, row, lanes, [&](int entry, int& s, int& typeJ) {
                s = entry;
                return by_codes(s, typeJ);
            }, by_codes);
        }
    }

    // Slot k's pairs with separations from the positions in R.
    template <bool kPlain = false>
    SMD_HD SMD_INLINE void over_positions(int64_t k, Lanes lanes) const {
        const NeighbourView<R>& v = neighbours;
        const int i = v.order[k];
        if (!kPlain && group && !group[i]) return;
        const Real4<R> pi = v.positions[k];
        const Params* row = table.row_of(i, kPlain ? 0 : static_cast<int>(pi.w));
        const Vec3<R> ri = xyz(pi);
        const auto separation = [&](int s, int& typeJ) {
            const Real4<R> pj = v.positions[s];
            typeJ = kPlain ? 0 : static_cast<int>(pj.w);
            return v.box.minimum_image(xyz(pj) - ri);
        };
        sum_pairs<R, kPlain>(k, i, row, lanes, [&](int entry, int& s, int& typeJ) {
            s = kPlain ? entry : v.slot_of_entry(entry);
            return separation(s, typeJ);
        }, separation);
    }

    // Slot k's terms with its neighbours, each lane's force in S (R, or float from cell-local
    // positions): listed(entry, s, typeJ) gives the separation of a list entry's pair, its slot s and
    // its particle's type, scanned(s, typeJ) those of a slot of an overflowed list's cells.
    // kPlain (one type, no group): the pair's parameters are read once, before the neighbours, and
    // no neighbour's group is looked up: some 8 instructions fewer a neighbour (sm_90).
    template <class S, bool kPlain, class Listed, class Scanned>
    SMD_HD SMD_INLINE void sum_pairs(int64_t k, int i, const Params* row, Lanes lanes, Listed&& listed,
                                     Scanned&& scanned) const {
        const NeighbourView<R>& v = neighbours;
        Vec3<S> laneForce{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        const Params only = row[0];  // read where kPlain alone
        const auto pair = [&](int s, int typeJ, const Vec3<S>& d) {
            const PairR r2 = PairR(dot(d, d));
            const Params& p = kPlain ? only : row[typeJ];
            if (!(r2 < p.cutoff2) || (!kPlain && group && !group[v.order[s]])) return;
            const PairTerm<PairR> t = evaluate_pair_of<Potential>(r2, p, charge, radius, i, v.order[s]);
            if (WantForce) laneForce += S(t.dudr_over_r) * d;
            if (WantEnergy) e += R(0.5) * R(t.energy);
            if (WantVirial) {
                const Vec3<R> rij{R(d.x), R(d.y), R(d.z)};
                w += (R(-0.5) * R(t.dudr_over_r)) * outer(rij, rij);
            }
        };
        v.for_each_entry(static_cast<int>(k), [&](int entry) {
            int s, typeJ;
            const Vec3<S> d = listed(entry, s, typeJ);
            pair(s, typeJ, d);
        }, [&](int s) {
            int typeJ;
            const Vec3<S> d = scanned(s, typeJ);
            pair(s, typeJ, d);
        }, lanes);
        Vec3<R> f{R(laneForce.x), R(laneForce.y), R(laneForce.z)};
        if (WantForce) f = lanes.sum(f);
        if (WantEnergy) e = lanes.sum(e);
        if (WantVirial) w = lanes.sum(w);
        if (lanes.leader()) add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w);
    }

#if SMD_HOST_CODE
    // The CPU backend's loop (backends/cpu/cpu_backend.hpp, for_each_lanes): slots begin .. end - 1 on
    // one thread, in PairRowsOnHost, whose one body serves every choice of outputs (asked for at run
    // time there), so that a term's unit compiles that large flattened loop once, not once a choice.
    // A slot it cannot take runs operator() of this kernel.
    void host_rows(int64_t begin, int64_t end) const {
        const PairRowsOnHost<Potential, R, PairR> loop{
            charge, radius, group, neighbours, table, out, WantForce, WantEnergy, WantVirial, this, &slot_by_operator,
        };
        loop.rows(begin, end);
    }
    static void slot_by_operator(const void* kernel, int64_t k) { (*static_cast<const PairKernel*>(kernel))(k, Lanes{}); }
#endif
};

#if SMD_HOST_CODE
// The CPU backend's loop of PairKernel (its host_rows) over slots begin .. end - 1 on one thread: the
// kernel's data, which outputs are asked for, and the kernel's operator() for a slot this loop does not
// take. One body for the seven choices of outputs: they differ in the last pass alone (sum_outputs).
template <class Potential, class R, class PairR>
struct PairRowsOnHost {
    using Params = typename Potential::template Params<PairR>;
    static constexpr bool kCellLocal = PairKernel<Potential, R, PairR, true, false, false>::kCellLocal;
    // PairKernel's data (its comments say what each is), then the outputs asked for.
    const R* charge;
    const R* radius;
    const uint8_t* group;
    NeighbourView<R> neighbours;
    PairTable<Params> table;
    ForceOutputs<R> out;
    bool wantForce, wantEnergy, wantVirial;
    const void* kernel;
    void (*slotByOperator)(const void* kernel, int64_t k);

    // Running sums of a slot's terms, one per lane of a vector (GCC's and Clang's vector extension).
    static constexpr int kSums = 4;
    typedef R Sums __attribute__((vector_size(kSums * sizeof(R))));

    // Each slot in three passes over per-thread arrays, the first and last of independent
    // iterations the compiler vectorises: the separations of every list entry, those within the
    // cutoff moved to the front (core/left_pack.hpp), and the pair terms of those alone.
    // Their sums then run in an order fixed by the pairs within the cutoff: the same after a rebuild
    // at another step, a restart, or in a spatial domain's list, whatever pairs beyond the cutoff
    // the list happens to hold. flatten: every call inlined (the box's minimum image, the
    // potential), which the inliner otherwise declines in a body this size. A slot of a group,
    // whose list overflowed, or of a list whose entries carry cells (not the CPU's) takes operator().
    SMD_HOST_LOOP void rows(int64_t begin, int64_t end) const {
        constexpr bool charges = uses_charges<Potential>(0), radii = uses_radii<Potential>(0);
        const NeighbourView<R>& v = neighbours;
        const int capacity = v.capacity > 0 ? v.capacity : 0;
        const size_t length = static_cast<size_t>(LeftPack<R>::padded(capacity));
        thread_local std::vector<R> scratch;
        if (scratch.size() < 10 * length) scratch.resize(10 * length);
        // By list entry, then packed: the separation, its square, and what the potential reads of
        // the partner (its type, when the types differ; its charge; its radius).
        R* const dx = scratch.data();
        R* const dy = dx + length;
        R* const dz = dy + length;
        R* const r2 = dz + length;
        R* const typeJ = r2 + length;
        R* const chargeJ = typeJ + length;
        R* const radiusJ = chargeJ + length;
        R* const within = radiusJ + length;  // 1 within the cutoff, else 0
        R* const g = within + length;        // dU/dr / r of the packed pairs
        R* const u = g + length;             // U of the packed pairs
        R* packed[7] = {dx, dy, dz, r2, typeJ};
        int packedArrays = 5;
        if (charges) packed[packedArrays++] = chargeJ;
        if (radii) packed[packedArrays++] = radiusJ;
        // One type and one table: the same parameters for every pair, kept out of the loops.
        const bool oneTable = table.ntypes == 1 && table.batch == nullptr;
        for (int64_t k = begin; k < end; ++k) {
            const int n = v.count[k];
            if (group || n > v.capacity || !v.by_rows() || v.entryShift) {
                slotByOperator(kernel, k);
                continue;
            }
            const int i = v.order[k];
            const Real4<R> pi = v.positions[k];
            const Vec3<R> ri = xyz(pi);
            const Params* row = table.row_of(i, static_cast<int>(pi.w));
            const int* entries = v.entries_of(k);
            const Real4<R>* const positions = v.positions;
            const int* const order = v.order;
            const Box<R> box = v.box;
            const Params first = row[0];
            // Element by element (no copies of whole structures, which keep the compiler from
            // turning the minimum image's branches into selects): entry m, slot s, its separation
            // and the square of it.
            const auto store = [&](int m, int s, R x, R y, R z, R squared) {
                dx[m] = x;
                dy[m] = y;
                dz[m] = z;
                r2[m] = squared;
                typeJ[m] = positions[s].w;
                if (charges) chargeJ[m] = charge[order[s]];
                if (radii) radiusJ[m] = radius[order[s]];
                within[m] = PairR(squared) < first.cutoff2 ? R(1) : R(0);
            };
            const auto separation = [&](int m) {
                const int s = entries[m];
                const Vec3<R> rij =
                    box.minimum_image(Vec3<R>{positions[s].x - ri.x, positions[s].y - ri.y, positions[s].z - ri.z});
                store(m, s, rij.x, rij.y, rij.z, dot(rij, rij));
            };
            // Mixed precision: the separations from the cell-local positions, as operator() takes them.
            const auto separation_in_cells = [&](int m, const CellLocalPositions<R>& local, const Real4<float>& li) {
                const int s = entries[m];
                const Vec3<float> rij = local.separation(li, local.local[s]);
                store(m, s, rij.x, rij.y, rij.z, dot(rij, rij));
            };
            if (kCellLocal && v.cellLocal.local) {
                const CellLocalPositions<R> local = v.cellLocal;
                const Real4<float> li = local.local[k];
#pragma omp simd
                for (int m = 0; m < n; ++m) separation_in_cells(m, local, li);
            } else {
#pragma omp simd
                for (int m = 0; m < n; ++m) separation(m);
            }
            if (!oneTable) {
                for (int m = 0; m < n; ++m)
                    within[m] = PairR(r2[m]) < row[static_cast<int>(typeJ[m])].cutoff2 ? R(1) : R(0);
            }
            for (int m = n; m < LeftPack<R>::padded(n); ++m) within[m] = R(0);
            const int kept = LeftPack<R>::pack(packed, packedArrays, within, n);
            const auto term = [&](int c, const Params& p) {
                const PairTerm<PairR> t =
                    evaluate_pair<Potential>(PairR(r2[c]), p, charges ? PairR(charge[i] * chargeJ[c]) : PairR(0),
                                             radii ? PairR(radius[i]) : PairR(0), radii ? PairR(radiusJ[c]) : PairR(0));
                g[c] = R(t.dudr_over_r);
                return R(t.energy);
            };
            // U stored only where it is summed, so that the potential's energy is not computed else.
            if (oneTable && wantEnergy) {
#pragma omp simd
                for (int c = 0; c < kept; ++c) u[c] = term(c, first);
            } else if (oneTable) {
#pragma omp simd
                for (int c = 0; c < kept; ++c) term(c, first);
            } else if (wantEnergy) {
                for (int c = 0; c < kept; ++c) u[c] = term(c, row[static_cast<int>(typeJ[c])]);
            } else {
                for (int c = 0; c < kept; ++c) term(c, row[static_cast<int>(typeJ[c])]);
            }
            sum_outputs(i, kept, g, u, dx, dy, dz);
        }
    }

    // Slot i's sums of its kept pair terms (dU/dr / r in g, U in u, the separations in dx, dy, dz),
    // added to the outputs asked for. Four running sums, term m into sum m % 4 (a vector's lanes),
    // added pairwise at the end: an order fixed by the pairs within the cutoff alone, the same on
    // every machine, whose four chains of additions run side by side where one chain of dependent
    // additions bounded the loop (and which the compiler cannot turn into an in-order reduction by
    // shuffles).
    void sum_outputs(int i, int kept, const R* g, const R* u, const R* dx, const R* dy, const R* dz) const {
        dispatch_wanted(wantForce, wantEnergy, wantVirial, [&](auto force, auto energy, auto virial) {
            sum_outputs<decltype(force)::value, decltype(energy)::value, decltype(virial)::value>(i, kept, g, u, dx, dy,
                                                                                                   dz);
        });
    }
    template <bool F, bool E, bool V>
    void sum_outputs(int i, int kept, const R* g, const R* u, const R* dx, const R* dy, const R* dz) const {
        Sums fx{}, fy{}, fz{}, e{}, w[9]{};
        int m = 0;
        for (; m + kSums <= kept; m += kSums) {
            Sums gm, x, y, z;
            std::memcpy(&gm, g + m, sizeof(Sums));
            std::memcpy(&x, dx + m, sizeof(Sums));
            std::memcpy(&y, dy + m, sizeof(Sums));
            std::memcpy(&z, dz + m, sizeof(Sums));
            if (F) {
                fx += gm * x;
                fy += gm * y;
                fz += gm * z;
            }
            if (E) {
                Sums um;
                std::memcpy(&um, u + m, sizeof(Sums));
                e += R(0.5) * um;
            }
            if (V) {
                const Sums h = R(-0.5) * gm, r[3] = {x, y, z};
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b) w[3 * a + b] += h * (r[a] * r[b]);
            }
        }
        for (int lane = 0; m + lane < kept; ++lane) {
            const int last = m + lane;
            if (F) {
                fx[lane] += g[last] * dx[last];
                fy[lane] += g[last] * dy[last];
                fz[lane] += g[last] * dz[last];
            }
            if (E) e[lane] += R(0.5) * u[last];
            if (V) {
                const R h = R(-0.5) * g[last], r[3] = {dx[last], dy[last], dz[last]};
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b) w[3 * a + b][lane] += h * (r[a] * r[b]);
            }
        }
        const auto total = [](const Sums& a) { return (a[0] + a[1]) + (a[2] + a[3]); };
        add_to_outputs<F, E, V>(out, i, Vec3<R>{total(fx), total(fy), total(fz)}, total(e),
                                Tensor3<R>{total(w[0]), total(w[1]), total(w[2]), total(w[3]), total(w[4]), total(w[5]),
                                           total(w[6]), total(w[7]), total(w[8])});
    }
};
#endif

// A PairKernel whose separations are chosen at launch: where the list keeps cell-local positions, the
// mixed-precision kernel runs over them alone, else over the positions alone, so that neither GPU
// kernel holds the other path's registers. Under the lone-lane kernel's register cap (one lane per
// particle, a large system) the two paths together spilled 208/236 bytes a thread (stores/loads,
// sm_90), the cell-local path alone 68/52, about single precision's 64/60. Plain: the kernel
// where plain() holds, launched for forces alone (a step's usual call).
template <class Kernel, bool OverCells, bool Plain = false>
struct PairKernelWithSeparations : Kernel {
    SMD_HD void operator()(int64_t k, Lanes lanes) const {
        if constexpr (OverCells)
            this->template over_cells<Plain>(k, lanes);
        else
            this->template over_positions<Plain>(k, lanes);
    }
};

}  // namespace structmd
