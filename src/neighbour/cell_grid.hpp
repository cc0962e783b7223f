#pragma once
// Division of the periodic box into cells at least as wide as the list radius divided by the reach,
// so that every neighbour of a particle lies within `reach` cells of its own along each axis: reach 1
// (27 cells) suits a GPU's lanes where several take a particle, a cell's members in rounds; reach 2
// (cells half as wide, 125 of them) lets a CPU core, or a GPU thread that takes a particle alone,
// skip the cells out of range of each particle and test about a third of the candidates of 27 wide
// cells. Independent systems sharing the
// box (batches) get a grid each, so a particle's candidates are those of its own batch only: 1,000
// batches overlaid in one box cost what one system of their total size costs, not 1,000 times more.
//
// Along an open axis (length infinity) the cells repeat: a coordinate x falls in cell
// floor(x / width) modulo the axis's cell count, so the grid stays finite however far the particles
// spread. Particles far apart along that axis may then share a cell; the distance test drops them,
// and the neighbours of a particle are still within `reach` cells of its own, modulo the count.
#include "core/box.hpp"

#if SMD_HOST_CODE
#include <algorithm>
#include <cmath>
#include <cstdint>
#endif

namespace structmd {

template <class R>
struct CellGrid {
    int nx = 1, ny = 1, nz = 1;
    int batches = 1;  // grids, one after the other: batch b's cells are b * nx * ny * nz onwards
    int reach = 1;    // cells scanned on each side of a particle's own along every axis
    Vec3<R> cellsPerLength{1, 1, 1};  // cells per unit length along each axis
    bool openX = false, openY = false, openZ = false;  // axes whose cells repeat (see above)

#if SMD_HOST_CODE
    int count() const { return nx * ny * nz * batches; }

    // Cells no narrower than radius / reach, and not many more cells than about twice the particles
    // so a dilute system in a large box does not allocate a huge grid. A reach above 1 is kept only
    // where every axis has more than 2 * reach cells (else reach 1), so the rows of a particle's
    // stencil are distinct cells.
    static CellGrid make(const Box<R>& box, double radius, int64_t particles, int batches = 1, int reach = 1) {
        CellGrid grid;
        grid.batches = std::max(batches, 1);
        grid.reach = std::max(reach, 1);
        const double minWidth = radius / grid.reach;
        const double length[3] = {static_cast<double>(box.length.x), static_cast<double>(box.length.y),
                                  static_cast<double>(box.length.z)};
        const bool open[3] = {is_open_axis(length[0]), is_open_axis(length[1]), is_open_axis(length[2])};
        const double limit = std::max<double>(64.0, 2.0 * static_cast<double>(particles));
        double n[3], periodicCells = 1.0;
        int openAxes = 0;
        for (int d = 0; d < 3; ++d) {
            n[d] = std::min(std::max(1.0, std::floor(length[d] / minWidth)), 1e6);  // NaN and huge ratios: 1 and 1e6
            if (open[d])
                ++openAxes;
            else
                periodicCells *= n[d];
        }
        // Open axes share what the periodic ones leave of the limit: a cube of cells about as many
        // as twice the particles where all are open, as wide as the list radius allows.
        for (int d = 0; d < 3; ++d)
            if (open[d])
                n[d] = std::max(1.0, std::floor(std::pow(limit / (periodicCells * grid.batches), 1.0 / openAxes)));
        while (n[0] * n[1] * n[2] * grid.batches > limit && n[0] * n[1] * n[2] > 1) {
            for (double& v : n) v = std::max(1.0, std::floor(v * 0.8));
        }
        if (grid.reach > 1 && std::min({n[0], n[1], n[2]}) <= 2.0 * grid.reach)
            return make(box, radius, particles, batches, 1);
        grid.nx = static_cast<int>(n[0]);
        grid.ny = static_cast<int>(n[1]);
        grid.nz = static_cast<int>(n[2]);
        const auto perLength = [&](int d) { return R(open[d] ? 1.0 / minWidth : n[d] / length[d]); };
        grid.cellsPerLength = {perLength(0), perLength(1), perLength(2)};
        grid.openX = open[0];
        grid.openY = open[1];
        grid.openZ = open[2];
        return grid;
    }

    // The volume the cells cover: along an open axis, one round of its repeating cells.
    double volume(const Box<R>& box) const {
        const auto span = [](double length, bool open, int n, R perLength) {
            return open ? n / static_cast<double>(perLength) : length;
        };
        return span(box.length.x, openX, nx, cellsPerLength.x) * span(box.length.y, openY, ny, cellsPerLength.y) *
               span(box.length.z, openZ, nz, cellsPerLength.z);
    }
#endif


    // The cell along an axis of n cells; a coordinate outside the box (a particle that blew up,
    // reported by the integrator) lands in an edge cell, and NaN in cell 0.
    static SMD_HD SMD_INLINE int cell_of(R scaled, int n) {
        const R c = floor(scaled);
        return c >= R(0) ? (c < R(n) ? static_cast<int>(c) : n - 1) : 0;
    }

    // A coordinate in units of cells, in [0, n) for a wrapped position (r in [-L/2, L/2)) and for any
    // position along an open axis, whose cells repeat. There it is reduced in double, so that
    // particles far from the origin still fall in the cells of their neighbours; NaN goes to 0.
    static SMD_HD SMD_INLINE R scaled_along(R r, R length, R perLength, bool open, int n) {
        if (!open) return (r + R(0.5) * length) * perLength;
        const double s = static_cast<double>(r) * static_cast<double>(perLength);
        const R wrapped = static_cast<R>(s - n * floor(s / n));
        return wrapped < R(n) ? wrapped : R(0);
    }
    SMD_HD SMD_INLINE Vec3<R> scaled(Vec3<R> r, const Box<R>& box) const {
        return {scaled_along(r.x, box.length.x, cellsPerLength.x, openX, nx),
                scaled_along(r.y, box.length.y, cellsPerLength.y, openY, ny),
                scaled_along(r.z, box.length.z, cellsPerLength.z, openZ, nz)};
    }

    // Cell coordinates of a wrapped position, or of any position along an open axis.
    SMD_HD SMD_INLINE void coordinates(Vec3<R> r, const Box<R>& box, int& cx, int& cy, int& cz) const {
        const Vec3<R> u = scaled(r, box);
        cx = cell_of(u.x, nx);
        cy = cell_of(u.y, ny);
        cz = cell_of(u.z, nz);
    }

    SMD_HD SMD_INLINE int index(int cx, int cy, int cz) const { return (cz * ny + cy) * nx + cx; }
    // The coordinates of the cell with this index in its batch's grid (index's inverse).
    SMD_HD SMD_INLINE void coordinates_of(int cell, int& cx, int& cy, int& cz) const {
        cx = cell % nx;
        cy = cell / nx % ny;
        cz = cell / (nx * ny) % nz;
    }
    SMD_HD SMD_INLINE int index(int cx, int cy, int cz, int batch) const {
        return (batch * nz + cz) * ny * nx + cy * nx + cx;
    }

    // First and last offset to scan along an axis of n cells: with 2 * reach cells or fewer the
    // offsets -reach and +reach would name the same cell twice, so each cell is named once.
    SMD_HD SMD_INLINE int last_offset(int n) const { return reach < (n - 1) / 2 ? reach : (n - 1) / 2; }
    SMD_HD SMD_INLINE int first_offset(int n) const {
        return -(reach < n - 1 - last_offset(n) ? reach : n - 1 - last_offset(n));
    }
    static SMD_HD SMD_INLINE int periodic(int c, int n) { return c < 0 ? c + n : (c >= n ? c - n : c); }

    // Whether the image of a wrapped position in an adjacent cell is the one the cell's offset names
    // (across the boundary where the offset wraps, else the position itself), for every pair closer
    // than the list radius: every periodic axis has at least 2 reach + 2 cells, so a neighbour cell
    // across the boundary is at least L / 2 away and one inside it less (the minimum image would
    // shift the same way). Open axes never wrap.
    SMD_HD SMD_INLINE bool images_by_offset() const {
        const auto fits = [this](int n, bool open) { return open || n >= 2 * reach + 2; };
        return fits(nx, openX) && fits(ny, openY) && fits(nz, openZ);
    }
    // The shift, along an axis of n cells and this length, that brings a position in the cell
    // `offset` cells from cell c to the image next to c: -length or +length where the offset wraps.
    static SMD_HD SMD_INLINE R image_shift(int c, int offset, int n, R length, bool open) {
        const int to = c + offset;
        return open ? R(0) : (to < 0 ? -length : (to >= n ? length : R(0)));
    }

    // Calls visit(cell, dx, dy, dz) once for each distinct cell within reach of (cx, cy, cz) in a
    // batch's grid, (dx, dy, dz) being its offset in cells from (cx, cy, cz) before the wrap.
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_adjacent_offset(int cx, int cy, int cz, int batch, Visit&& visit) const {
        for (int dz = first_offset(nz); dz <= last_offset(nz); ++dz)
            for (int dy = first_offset(ny); dy <= last_offset(ny); ++dy)
                for (int dx = first_offset(nx); dx <= last_offset(nx); ++dx)
                    visit(index(periodic(cx + dx, nx), periodic(cy + dy, ny), periodic(cz + dz, nz), batch), dx, dy,
                          dz);
    }

    // Distance, in cells, from the coordinate u (in cells, inside cell c) to the cell `offset`
    // cells from c along the same axis: 0 for c itself.
    static SMD_HD SMD_INLINE R gap(R u, int c, int offset) {
        const R g = offset > 0 ? R(c + offset) - u : (offset < 0 ? u - R(c + offset + 1) : R(0));
        return g > R(0) ? g : R(0);
    }

    // radius2 grown by what rounding may take off a distance measured from the cells' geometry: a
    // thousandth of the radius, and a millionth of the grid's extent (a float coordinate's ulp is
    // 1.2e-7 of it, which a dilute system's large box makes larger than the thousandth), so that
    // skipping the cells beyond it never drops a pair the exact distance test would accept.
    SMD_HD SMD_INLINE R pruning_radius2(R radius2) const {
        const R ex = R(nx) / cellsPerLength.x, ey = R(ny) / cellsPerLength.y, ez = R(nz) / cellsPerLength.z;
        const R extent = ex > ey ? (ex > ez ? ex : ez) : (ey > ez ? ey : ez);
        const R radius = sqrt(radius2) * R(1.001) + R(1e-6) * extent;
        return radius * radius;
    }

    // Whether the cells around the point u (in cells) can be skipped by their distance from it: u
    // inside the grid (not NaN, not a particle that blew up out of the box, so the cell arithmetic
    // stays in the range of an int), and more than 2 reach cells along every axis (offsets that
    // name distinct cells).
    SMD_HD SMD_INLINE bool prunable_at(Vec3<R> u) const {
        const bool inside = u.x >= R(0) && u.x < R(nx) && u.y >= R(0) && u.y < R(ny) && u.z >= R(0) && u.z < R(nz);
        return inside && nx > 2 * reach && ny > 2 * reach && nz > 2 * reach;
    }

    // for_each_adjacent_offset(), less the cells that lie radius2 or farther from the point u (in
    // cells, inside cell (cx, cy, cz)), in runs: visit(first, last, dx, dy, dz) for the cells
    // first .. last, consecutive in a row along x, whose first is dx cells from cx before the wrap,
    // in the order of increasing dz, dy, dx. A row's cells within the radius are one range of
    // offsets (a cell's gap grows away from cx), split in two where it wraps across the periodic
    // boundary; their slots are then one range too, so a list build takes a row's candidates in
    // rounds of its lanes and reads two cell bounds a run, not two a cell. A sphere about a point of
    // the middle cell reaches about 21 of 27 cells as wide as its radius, and about 84 of 125 cells
    // half as wide: a list build over the narrow cells tests about 40% fewer candidates than over
    // the 27 wide ones. A caller that must not miss a pair passes pruning_radius2() of its radius.
    // Where the cells are not prunable_at(u), every cell within reach, each a run of its own; so too
    // every cell where kWholeRuns is false, for a caller whose work differs from cell to cell.
    template <bool kWholeRuns, class Visit>
    SMD_HD SMD_INLINE void for_each_run_near(Vec3<R> u, int cx, int cy, int cz, int batch, R radius2,
                                             Visit&& visit) const {
        if (!prunable_at(u)) {
            for_each_adjacent_offset(cx, cy, cz, batch, [&](int c, int dx, int dy, int dz) { visit(c, c, dx, dy, dz); });
            return;
        }
        const Vec3<R> width{R(1) / cellsPerLength.x, R(1) / cellsPerLength.y, R(1) / cellsPerLength.z};
        for (int dz = -reach; dz <= reach; ++dz) {
            const R gz = gap(u.z, cz, dz) * width.z;
            const R leftZ = radius2 - gz * gz;
            if (leftZ <= R(0)) continue;
            const int pz = periodic(cz + dz, nz);
            for (int dy = -reach; dy <= reach; ++dy) {
                const R gy = gap(u.y, cy, dy) * width.y;
                const R left = leftZ - gy * gy;
                if (left <= R(0)) continue;
                if (!kWholeRuns) {
                    const int py = periodic(cy + dy, ny);
                    for (int dx = -reach; dx <= reach; ++dx) {
                        const R gx = gap(u.x, cx, dx) * width.x;
                        if (gx * gx >= left) continue;
                        const int c = index(periodic(cx + dx, nx), py, pz, batch);
                        visit(c, c, dx, dy, dz);
                    }
                    continue;
                }
                int low = 0, high = 0;  // the offsets along x within the radius
                for (int dx = -reach; dx <= reach; ++dx) {
                    const R gx = gap(u.x, cx, dx) * width.x;
                    if (gx * gx < left) {
                        low = dx < low ? dx : low;
                        high = dx > high ? dx : high;
                    }
                }
                // One call of visit for both parts of a wrapped row: each call site inlines the
                // caller's whole candidate loop.
                const int row = index(0, periodic(cy + dy, ny), pz, batch);
                int dx = low;
                do {
                    const int x = periodic(cx + dx, nx);
                    const int more = high - dx < nx - 1 - x ? high - dx : nx - 1 - x;  // up to the row's end
                    visit(row + x, row + x + more, dx, dy, dz);
                    dx += more + 1;
                } while (dx <= high);
            }
        }
    }

    // Calls visit(cell) once for each distinct cell within reach of (cx, cy, cz) in a batch's grid.
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_adjacent(int cx, int cy, int cz, int batch, Visit&& visit) const {
        for_each_adjacent_offset(cx, cy, cz, batch, [&](int c, int, int, int) { visit(c); });
    }
};

}  // namespace structmd
