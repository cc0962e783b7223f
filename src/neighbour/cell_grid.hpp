#pragma once
// Division of the periodic box into cells at least as wide as the list radius divided by the reach,
// so that every neighbour of a particle lies within `reach` cells of its own along each axis: reach 1
// (27 cells) suits a GPU's lanes, which take a cell's members in rounds; reach 2 (cells half as wide,
// 125 of them) lets a CPU core skip the rows of cells out of range of each particle and scan about
// a third of the candidates of 27 wide cells. Independent systems sharing the
// box (batches) get a grid each, so a particle's candidates are those of its own batch only: 1,000
// batches overlaid in one box cost what one system of their total size costs, not 1,000 times more.
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
        double n[3] = {std::floor(box.length.x / minWidth), std::floor(box.length.y / minWidth),
                       std::floor(box.length.z / minWidth)};
        for (double& v : n) v = std::min(std::max(1.0, v), 1e6);  // NaN and huge ratios: 1 and 1e6
        const double limit = std::max<double>(64.0, 2.0 * static_cast<double>(particles));
        while (n[0] * n[1] * n[2] * grid.batches > limit && n[0] * n[1] * n[2] > 1) {
            for (double& v : n) v = std::max(1.0, std::floor(v * 0.8));
        }
        if (grid.reach > 1 && std::min({n[0], n[1], n[2]}) <= 2.0 * grid.reach)
            return make(box, radius, particles, batches, 1);
        grid.nx = static_cast<int>(n[0]);
        grid.ny = static_cast<int>(n[1]);
        grid.nz = static_cast<int>(n[2]);
        grid.cellsPerLength = {R(grid.nx / static_cast<double>(box.length.x)),
                               R(grid.ny / static_cast<double>(box.length.y)),
                               R(grid.nz / static_cast<double>(box.length.z))};
        return grid;
    }
#endif


    // The cell along an axis of n cells; a coordinate outside the box (a particle that blew up,
    // reported by the integrator) lands in an edge cell, and NaN in cell 0.
    static SMD_HD SMD_INLINE int cell_of(R scaled, int n) {
        const R c = floor(scaled);
        return c >= R(0) ? (c < R(n) ? static_cast<int>(c) : n - 1) : 0;
    }

    // Cell coordinates of a wrapped position (r in [-L/2, L/2)).
    SMD_HD SMD_INLINE void coordinates(Vec3<R> r, const Box<R>& box, int& cx, int& cy, int& cz) const {
        cx = cell_of((r.x + R(0.5) * box.length.x) * cellsPerLength.x, nx);
        cy = cell_of((r.y + R(0.5) * box.length.y) * cellsPerLength.y, ny);
        cz = cell_of((r.z + R(0.5) * box.length.z) * cellsPerLength.z, nz);
    }

    SMD_HD SMD_INLINE int index(int cx, int cy, int cz) const { return (cz * ny + cy) * nx + cx; }
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

    // Calls visit(cell) once for each distinct cell within reach of (cx, cy, cz) in a batch's grid.
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_adjacent(int cx, int cy, int cz, int batch, Visit&& visit) const {
        for (int dz = first_offset(nz); dz <= last_offset(nz); ++dz)
            for (int dy = first_offset(ny); dy <= last_offset(ny); ++dy)
                for (int dx = first_offset(nx); dx <= last_offset(nx); ++dx)
                    visit(index(periodic(cx + dx, nx), periodic(cy + dy, ny), periodic(cz + dz, nz), batch));
    }
};

}  // namespace structmd
