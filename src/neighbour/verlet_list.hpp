#pragma once
// Cell list feeding a Verlet list with a skin, over the particles sorted by cell (neighbour_view.hpp).
// The list is rebuilt only when some particle has moved more than half the skin since the last
// build; that test and the rebuild run on the backend without a host round trip. The list capacity
// adapts at API boundaries (adapt()), never inside the step.
//
// A list may also keep cluster pairs (cluster_view.hpp), for the pair kernels that traverse them; the
// per-particle lists are then built only once some caller has asked for their view (until then a view
// of them scans the cells, which is exact, only slower).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/error.hpp"
#include "neighbour/cluster_list_kernels.hpp"
#include "neighbour/pair_filter_inputs.hpp"
#include "neighbour/verlet_list_kernels.hpp"

namespace structmd {

template <class B, class R>
class VerletList {
public:
    // inputs: what the condition reads about each particle (exclusions, types, charges); batch
    // (numbered 0 .. batches - 1) and model: backend arrays by particle, or null where not needed.
    // clusters: keep cluster pairs as well, where the list accepts every pair of one system (no
    // condition, no exclusions, no batches), which is what the cluster kernels handle.
    VerletList(const B& backend, double cutoff, double verletFactor, PairCondition condition,
               const PairFilterInputs& inputs, const int* batch, int batches, const int* model,
               bool clusters = false)
        : backend_(backend),
          cutoff_(cutoff),
          listRadius_(cutoff * verletFactor),
          batch_(batch),
          batches_(batches),
          clustersAllowed_(clusters && condition == PairCondition::all && inputs.excluded.empty() && !batch &&
                           batches <= 1) {
        backend_.resize(control_, kControlSlots);
        backend_.fill(control_, 0);
        filter_.condition = condition;
        filter_.model = model;
        if (!inputs.kind.empty()) {
            backend_.upload(kind_, inputs.kind.data(), inputs.kind.size());
            filter_.kind = kind_.data();
        }
        if (!inputs.charged.empty()) {
            backend_.upload(charged_, inputs.charged.data(), inputs.charged.size());
            filter_.charged = charged_.data();
        }
        if (!inputs.excluded.empty()) {
            std::vector<int> start(1, 0), flat;
            for (const auto& ids : inputs.excluded) {
                flat.insert(flat.end(), ids.begin(), ids.end());
                start.push_back(static_cast<int>(flat.size()));
            }
            backend_.upload(excludedStart_, start.data(), start.size());
            backend_.upload(excluded_, flat.data(), flat.size());
            filter_.excludedStart = excludedStart_.data();
            filter_.excluded = excluded_.data();
        }
    }

    double cutoff() const { return cutoff_; }
    double skin() const { return listRadius_ - cutoff_; }

    // Whether its per-particle lists offer every pair closer than `cutoff` among the particles of one
    // batch of `batch`'s numbering: no condition, no exclusions, and no cluster pairs (whose lists a
    // view() would have built beside them, changing what the steps pay).
    bool offers_every_pair_within(double cutoff, const int* batch) const {
        return filter_.trivial() && cutoff <= cutoff_ && batch == batch_ && !clustersAllowed_;
    }

    // Brings the list up to date for the positions in pos (wrapped, n particles); version names
    // those positions, so asking twice for the same ones costs nothing.
    void update(const typename B::template Buffer<Real4<R>>& pos, int64_t n, const Box<R>& box, int64_t version) {
        if (version == updatedAt_ && !forceRebuild_ && !needsLayout_) return;
        updatedAt_ = version;
        source_ = pos.data();
        if (needsLayout_ || n != particles_ || !same_box(box)) layout(n, box);
        // The flag is down between updates (the build lowers it), so a step without a build sets
        // nothing here and launches nothing of the build.
        if (forceRebuild_)
            backend_.write(control_, kRebuild, 1);
        else if (mirroredAt_ != version)
            backend_.for_each(n, RefreshPositions<R>{pos.data(), order_.data(), mirror()});
        if (forceRebuild_) particleListsBuilt_ = particleListsWanted_ || !clusters_;
        forceRebuild_ = false;
        backend_.only_if(control_.data() + kRebuild, [&] { build(pos, n); });
    }

    // Reads what the last builds needed (one small copy to the host) and enlarges the list
    // capacity if it was exceeded, so later builds store every neighbour in the list again.
    void adapt() {
        if (particles_ == 0) return;
        int control[kControlSlots];
        backend_.download(control_, control, kControlSlots);
        builds_ = control[kBuilds];
        // The new capacity takes effect at the next layout, together with the buffers sized for
        // it: until then every view keeps describing the buffers as they are.
        if (control[kMaxNeighbours] > capacity_) {
            pendingCapacity_ = control[kMaxNeighbours] + control[kMaxNeighbours] / 4 + 8;
            needsLayout_ = true;
        }
        if (clusters_ && control[kMaxPartnerClusters] > clusterCapacity_) {
            pendingClusterCapacity_ = control[kMaxPartnerClusters] + control[kMaxPartnerClusters] / 8 + 4;
            needsLayout_ = true;
        }
    }

    void invalidate() { forceRebuild_ = true; }

    // A pair kernel that evaluates in float over positions in double asks for the positions relative
    // to their cells in float as well (state/cell_local_positions.hpp); kept where the grid allows.
    void keep_cell_local_positions() { cellLocalWanted_ = true; }

    // Neighbours a particle the list has room for (or will have at its next layout); reserve()
    // raises it before the first layout.
    int capacity() const { return std::max(capacity_, pendingCapacity_); }
    void reserve(int neighbours) { pendingCapacity_ = std::max(pendingCapacity_, neighbours); }

    // What a drift kernel moving the n positions in `pos` needs to keep this list's copy and
    // displacement check (state/drift_bookkeeping.hpp): null slots unless the list is laid out for
    // exactly those positions (not, say, for sites placed from them) and is not to be built again
    // anyway (its copy may belong to other particles: a spatial domain's slots renumbered in place).
    const int* slot_of(const Real4<R>* pos, int64_t n) const {
        return particles_ == n && n > 0 && source_ == pos && !needsLayout_ && !forceRebuild_ ? slotOf_.data()
                                                                                               : nullptr;
    }
    // Where the list keeps cell-local positions and no caller has read its positions by slot yet
    // (view()), the mirror leaves them out: the cell-local pair kernels read their w (the type, set
    // by the build) alone, and a step writes 32 bytes a particle less (mixed precision).
    SlotMirror<R> mirror() {
        const R halfSkin = R(0.5 * (listRadius_ - cutoff_));
        return SlotMirror<R>{positions_read() ? positions_.data() : nullptr, binned_.data(), box_,
                             halfSkin * halfSkin, control_.data(), cell_local()};
    }
    // A drift kernel mirrored the positions of `version` (every particle's), the slots' positions
    // among them or not (`withPositions`). Without them where a view() has asked for them since
    // the drift was armed (an integrator whose step begins with the last one's armed drift), the
    // next update copies them instead.
    void mirrored(int64_t version, bool withPositions) {
        if (withPositions || !positions_read()) mirroredAt_ = version;
    }
    int64_t builds() const { return builds_; }

    // The per-particle lists. With clusters, the first call has them built from the next update on.
    // The slots' positions are this update's: the first call copies them where the mirror had left
    // them out, and from then on the mirror keeps them.
    NeighbourView<R> view() {
        const bool copy = !positions_read() && source_ && particles_ > 0;
        positionsRead_ = true;
        if (copy) backend_.for_each(particles_, RefreshPositions<R>{source_, order_.data(), mirror()});
        return cell_local_view();
    }
    // The same lists for a pair kernel that takes its separations from the cell-local positions where
    // they are kept (view.cellLocal.local) and reads only the w (type) of the slots' positions there.
    NeighbourView<R> cell_local_view() {
        if (clusters_ && !particleListsWanted_) {
            particleListsWanted_ = true;
            forceRebuild_ = true;
        }
        NeighbourView<R> v = particle_view();
        if (!particleListsBuilt_) v.capacity = -1;  // every count exceeds it: the cells are scanned
        return v;
    }

    // Whether the cluster pairs are kept (for the layout of the last update).
    bool clusters() const { return clusters_; }
    ClusterView<R> cluster_view() const {
        ClusterView<R> v;
        v.positions = positions_.data();
        v.order = order_.data();
        v.bounds = clusterBounds_.data();
        v.cellOf = clusterCell_.data();
        v.list = clusterList_.data();
        v.count = clusterCount_.data();
        v.capacity = clusterCapacity_;
        v.clusters = clusterIds_;
        v.cellStart = cellStart_.data();
        v.grid = grid_;
        v.box = box_;
        return v;
    }

private:
    NeighbourView<R> particle_view() {
        NeighbourView<R> v;
        v.positions = positions_.data();
        v.binned = binned_.data();
        v.order = order_.data();
        v.list = list_.data();
        v.count = count_.data();
        v.capacity = capacity_;
        constexpr int kChunk = NeighbourView<R>::kChunk;
        if (backend_.lists_by_rows(particles_)) {
            v.particleStride = capacity_;
            v.chunkStride = kChunk;
        } else {
            v.particleStride = kChunk;
            v.chunkStride = kChunk * particles_;
        }
        v.cellStart = cellStart_.data();
        v.grid = grid_;
        v.batch = batch_;
        v.box = box_;
        v.filter = filter_;
        v.cellLocal = cell_local();
        // The cells' offset in the entries of the GPU's lists, by columns or rows, whose pair kernels
        // then skip unpacking the cells' codes: LJ 52 -> 42 SASS instructions a neighbour in mixed
        // precision with one thread a particle, sm_90.
        if (v.cellLocal.local && backend_.list_entries_carry_cells() && particles_ <= CellLocalPositions<R>::kMostEntrySlots)
            v.entryShift = CellLocalPositions<R>::kOffsetBits;
        return v;
    }

    CellLocalPositions<R> cell_local() {
        CellLocalPositions<R> local;
        if (!cellLocalKept_) return local;
        local.local = cellLocal_.data();
        local.set_width({R(box_.length.x / grid_.nx), R(box_.length.y / grid_.ny), R(box_.length.z / grid_.nz)});
        local.halfLength = {R(0.5) * box_.length.x, R(0.5) * box_.length.y, R(0.5) * box_.length.z};
        local.set_cells(grid_.nx, grid_.ny, grid_.nz);
        return local;
    }

    bool positions_read() const { return positionsRead_ || !cellLocalKept_; }

    bool same_box(const Box<R>& box) const {
        return box.length.x == box_.length.x && box.length.y == box_.length.y && box.length.z == box_.length.z;
    }

    void build(const typename B::template Buffer<Real4<R>>& pos, int64_t n) {
        const int cells = grid_.count();
        backend_.for_each(n, BinParticles<R>{pos.data(), grid_, batch_, box_, control_.data(), cellCount_.data(),
                                             cellOf_.data(), rankInCell_.data()});
        backend_.for_each_lanes(chunks_, SumCellChunks{control_.data(), cellCount_.data(), chunkTotal_.data(),
                                                       chunkCells_, cells}, LaneSizing::kFillDevice);
        backend_.for_each_lanes(chunks_, StartCells{control_.data(), cellCount_.data(), chunkTotal_.data(),
                                              cellStart_.data(), chunkCells_, cells}, LaneSizing::kFillDevice);
        backend_.for_each(n, PlaceParticles{control_.data(), cellOf_.data(), rankInCell_.data(), cellStart_.data(),
                                            order_.data()});
        if (clusters_) {
            backend_.for_each(cells, SortCellsIntoClusters<R>{pos.data(), control_.data(), cellStart_.data(), grid_,
                                                              box_, order_.data(), slotOf_.data(), positions_.data(),
                                                              binned_.data(), clusterBounds_.data(),
                                                              clusterCell_.data(), clusterCentre_.data(),
                                                              clusterHalfExtent_.data()});
            backend_.for_each_lanes(clusterIds_,
                                    BuildClusterPairs<R>{cluster_view(), clusterCentre_.data(), clusterHalfExtent_.data(),
                                                         R(listRadius_ * listRadius_), control_.data(),
                                                         clusterList_.data(), clusterCount_.data()},
                                    LaneSizing::kFillDevice);
        } else {
            backend_.for_each(cells, SortCells<R>{pos.data(), control_.data(), cellStart_.data(), order_.data(),
                                                  slotOf_.data(), positions_.data(), binned_.data(), grid_,
                                                  cell_local(), box_});
        }
        if (particleListsBuilt_)
            with_build_path(BuildLists<R>{particle_view(), R(listRadius_ * listRadius_), control_.data(),
                                          B::ordered_neighbour_lists},
                            [&](const auto& along) { backend_.for_each_lanes(n, along, LaneSizing::kFillDevice); });
        backend_.write(control_, kRebuild, 0);
    }

    // Whether cell-local positions work over this grid: cells' distances fold across the boundary
    // once (periodic axes of 2 reach + 1 cells or more, a reach of at most 2, whose multiples of a
    // float width are exact) and the cells' codes are exact in float.
    static bool keeps_cell_local(const CellGrid<R>& grid) {
        const auto foldable = [&](int cells, bool open) { return !open && grid.reach <= 2 && cells > 2 * grid.reach; };
        return foldable(grid.nx, grid.openX) && foldable(grid.ny, grid.openY) && foldable(grid.nz, grid.openZ) &&
               CellLocalPositions<R>::codes_fit(grid.nx, grid.ny, grid.nz);
    }

    // Sizes every buffer for n particles in this box and schedules a full rebuild.
    void layout(int64_t n, const Box<R>& box) {
        box_ = box;
        capacity_ = std::max(capacity_, pendingCapacity_);
        // The cluster kernels take their partners from the 27 cells around a cluster.
        grid_ = CellGrid<R>::make(box, listRadius_, n, batches_, clustersAllowed_ ? 1 : backend_.list_cell_reach(n));
        // Cell-local positions need codes a float holds: cells twice as wide where half-width ones
        // have too many (16 million LJ particles) and the wide ones keep them.
        if (cellLocalWanted_ && grid_.reach > 1 && !keeps_cell_local(grid_)) {
            const CellGrid<R> wide = CellGrid<R>::make(box, listRadius_, n, batches_, 1);
            if (keeps_cell_local(wide)) grid_ = wide;
        }
        if (capacity_ == 0) {
            // No particle has more neighbours than there are particles, whatever the list radius;
            // batches overlaid in the box each fill it at their own density (over an open axis, as
            // if spread over one round of its cells: adapt() grows the lists of a denser cluster).
            const double volume = grid_.volume(box) * batches_;
            const double expected = 4.18879 * listRadius_ * listRadius_ * listRadius_ * n / volume;
            capacity_ = static_cast<int>(std::min(std::ceil(1.3 * expected), static_cast<double>(n))) + 16;
        }
        // Whole chunks of entries (neighbour_view.hpp).
        constexpr int kChunk = NeighbourView<R>::kChunk;
        capacity_ = (capacity_ + kChunk - 1) / kChunk * kChunk;
        particles_ = n;
        // About as many chunks as cells per chunk, so both passes of the scan of the cell counts
        // are short, and whole rounds of a warp's lanes per chunk.
        const int cells = grid_.count();
        chunkCells_ = 32 * static_cast<int>(std::ceil(std::sqrt(static_cast<double>(cells)) / 32));
        chunks_ = (cells + chunkCells_ - 1) / chunkCells_;
        // Kept allocations while they have room: a spatial domain's slot count changes at every
        // rebuild of its domains, by a little.
        backend_.fit(list_, static_cast<size_t>(capacity_) * n);
        backend_.fit(count_, n);
        backend_.fit(order_, n);
        backend_.fit(slotOf_, n);
        backend_.fit(positions_, n);
        backend_.fit(binned_, n);
        backend_.fit(cellOf_, n);
        backend_.fit(rankInCell_, n);
        backend_.resize(cellCount_, cells);
        backend_.fill(cellCount_, 0);
        backend_.resize(cellStart_, cells + 1);
        backend_.resize(chunkTotal_, chunks_);
        // Clusters need the minimum image of two bounding boxes' centres to be the one of their
        // particles: four cells or more along every axis.
        clusters_ = clustersAllowed_ && grid_.nx >= 4 && grid_.ny >= 4 && grid_.nz >= 4;
        cellLocalKept_ = cellLocalWanted_ && !clusters_ && keeps_cell_local(grid_);
        if (cellLocalKept_) backend_.fit(cellLocal_, n);
        if (clusters_) {
            clusterIds_ = static_cast<int>(n / kClusterSize) + cells;
            if (clusterCapacity_ == 0) {
                // About a third of the clusters of the 27 cells around a cluster have a particle
                // within reach of its own (59 of 180 in the LJ liquid); adapt() grows the lists
                // when more do.
                const double perCell = static_cast<double>(n) / cells / kClusterSize + 1.0;
                clusterCapacity_ = static_cast<int>(std::ceil(0.6 * 27.0 * perCell)) + 8;
            }
            clusterCapacity_ = std::max(clusterCapacity_, pendingClusterCapacity_);
            backend_.fit(clusterBounds_, 2 * static_cast<size_t>(clusterIds_));
            backend_.fit(clusterCell_, clusterIds_);
            backend_.fit(clusterCentre_, clusterIds_);
            backend_.fit(clusterHalfExtent_, clusterIds_);
            backend_.fit(clusterCount_, clusterIds_);
            backend_.fit(clusterList_, static_cast<size_t>(clusterCapacity_) * clusterIds_);
        }
        needsLayout_ = false;
        forceRebuild_ = true;
    }

    const B& backend_;
    double cutoff_;
    double listRadius_;
    const int* batch_;
    int batches_;
    int64_t particles_ = 0;
    Box<R> box_{};
    CellGrid<R> grid_;
    int capacity_ = 0;
    int pendingCapacity_ = 0;  // raised by adapt(), applied by layout()
    int chunkCells_ = 1;       // cells per chunk of the scan of cell counts
    int chunks_ = 0;
    bool needsLayout_ = true;
    bool forceRebuild_ = true;
    int64_t builds_ = 0;
    int64_t updatedAt_ = -1;
    const bool clustersAllowed_;
    bool clusters_ = false;              // cluster pairs kept for the current layout
    bool particleListsWanted_ = false;   // some caller asked for the per-particle lists
    bool particleListsBuilt_ = true;     // the builds since the last forced one made them
    bool cellLocalWanted_ = false;       // some pair kernel asked for cell-local positions
    bool cellLocalKept_ = false;         // and the current layout keeps them
    bool positionsRead_ = false;         // some caller read the slots' positions (view())
    int clusterIds_ = 0;
    int clusterCapacity_ = 0;
    int pendingClusterCapacity_ = 0;
    int64_t mirroredAt_ = -1;  // the positions version a drift kernel mirrored
    const Real4<R>* source_ = nullptr;  // the positions the list was last brought up to date with
    PairFilter filter_;
    typename B::template Buffer<int> excludedStart_, excluded_, kind_;
    typename B::template Buffer<uint8_t> charged_;
    typename B::template Buffer<int> control_;
    typename B::template Buffer<int> list_, count_, order_, slotOf_, cellOf_, rankInCell_, cellCount_, cellStart_, chunkTotal_;
    typename B::template Buffer<Real4<R>> positions_, binned_;
    typename B::template Buffer<Real4<float>> cellLocal_;
    typename B::template Buffer<int> clusterBounds_, clusterCell_, clusterList_, clusterCount_;
    typename B::template Buffer<Real4<R>> clusterCentre_, clusterHalfExtent_;
};

}  // namespace structmd
