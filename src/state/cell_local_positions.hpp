#pragma once
// A neighbour list's positions in float, each relative to the centre of the cell where the list last
// binned it: what a mixed-precision pair kernel reads of a neighbour. Half the bytes of the double
// positions, gathered once per list entry, and a separation whose rounding is that of a cell's width
// (about 1e-7 of a few sigma), not of the box's: taken in float from absolute positions it would grow
// with the box (ulp(L / 2), 4e-6 at a million LJ particles).
//
// The cell's coordinates travel in w, packed as cx + 256 cy + 65536 cz, an integer that a float holds
// exactly. Two particles of a pair within the cutoff were in the same or adjacent cells at the build
// (within `reach` cells), so their separation is the difference of their local positions plus the
// difference of their cells, folded once across the periodic boundary: no minimum image of the box.
// Kept only where every axis is periodic and has 2 reach + 1 to 256 cells (verlet_list.hpp).
#include "core/box.hpp"

namespace structmd {

template <class R>
struct CellLocalPositions {
    static constexpr int kAxisBits = 8;
    static constexpr int kAxisCells = 1 << kAxisBits;  // the most cells along an axis that w packs

    Real4<float>* local = nullptr;  // by slot; null: not kept
    Vec3<R> width{R(0), R(0), R(0)};  // a cell's edge along each axis
    // The width as the sum of two floats, hi + lo: the cells' distance, a small integer times it,
    // then keeps the width's double precision, whose float rounding (1e-7 of it) would otherwise be
    // the largest error of a separation. Kept here, where a GPU kernel reads them as operands of
    // its instructions without holding registers for them.
    Vec3<float> widthHi{0.0f, 0.0f, 0.0f}, widthLo{0.0f, 0.0f, 0.0f};
    Vec3<R> halfLength{R(0), R(0), R(0)};
    int nx = 1, ny = 1, nz = 1;
    int reach = 1;  // cells between a particle's cell and its neighbours' along each axis

    static SMD_HD SMD_INLINE float pack(int cx, int cy, int cz) {
        return static_cast<float>(cx | cy << kAxisBits | cz << 2 * kAxisBits);
    }
    static SMD_HD SMD_INLINE int cell_x(int code) { return code & (kAxisCells - 1); }
    static SMD_HD SMD_INLINE int cell_y(int code) { return code >> kAxisBits & (kAxisCells - 1); }
    static SMD_HD SMD_INLINE int cell_z(int code) { return code >> 2 * kAxisBits; }

    // The position x (wrapped or not) relative to the centre of the cell packed in `cell`.
    SMD_HD SMD_INLINE Real4<float> of(const Vec3<R>& x, float cell, const Box<R>& box) const {
        const int code = static_cast<int>(cell);
        const Vec3<R> centre{(R(cell_x(code)) + R(0.5)) * width.x - halfLength.x,
                             (R(cell_y(code)) + R(0.5)) * width.y - halfLength.y,
                             (R(cell_z(code)) + R(0.5)) * width.z - halfLength.z};
        const Vec3<R> d = box.minimum_image(x - centre);
        return {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z), cell};
    }

#if SMD_HOST_CODE
    void set_width(const Vec3<R>& edge) {
        width = edge;
        widthHi = {static_cast<float>(edge.x), static_cast<float>(edge.y), static_cast<float>(edge.z)};
        widthLo = {static_cast<float>(edge.x - R(widthHi.x)), static_cast<float>(edge.y - R(widthHi.y)),
                   static_cast<float>(edge.z - R(widthHi.z))};
    }
#endif

    // b - a for two slots' local positions: their difference plus the cells' distance, each axis's
    // folded across the periodic boundary.
    SMD_HD SMD_INLINE Vec3<float> separation(const Real4<float>& a, const Real4<float>& b) const {
        const int ca = static_cast<int>(a.w), cb = static_cast<int>(b.w);
        const auto along = [this](float d, int from, int to, int n, float hi, float lo) {
            const int c = to - from;
            const float cells = static_cast<float>(c > reach ? c - n : (c < -reach ? c + n : c));
            return (cells * hi + d) + cells * lo;  // cells * hi exact: |cells| <= reach <= 2
        };
        return {along(b.x - a.x, cell_x(ca), cell_x(cb), nx, widthHi.x, widthLo.x),
                along(b.y - a.y, cell_y(ca), cell_y(cb), ny, widthHi.y, widthLo.y),
                along(b.z - a.z, cell_z(ca), cell_z(cb), nz, widthHi.z, widthLo.z)};
    }

    // The cells' distance that separation() adds for cells a given number apart along each axis,
    // as its hi and lo parts (each product exact). A list build takes a whole cell's candidates at
    // one such shift and unpacks no cell per candidate; the pair kernel, whose neighbours' cells
    // differ, keeps separation() above (with the shift as a variable it spilled more registers).
    struct CellShift {
        Vec3<float> hi, lo;
    };
    SMD_HD SMD_INLINE CellShift shift(int cellsX, int cellsY, int cellsZ) const {
        const float x = static_cast<float>(cellsX), y = static_cast<float>(cellsY), z = static_cast<float>(cellsZ);
        return {{x * widthHi.x, y * widthHi.y, z * widthHi.z}, {x * widthLo.x, y * widthLo.y, z * widthLo.z}};
    }
    // separation(a, b) for local positions whose cells are `cells` apart: the same sums.
    static SMD_HD SMD_INLINE Vec3<float> separation(const Real4<float>& a, const Real4<float>& b, const CellShift& cells) {
        return {(cells.hi.x + (b.x - a.x)) + cells.lo.x, (cells.hi.y + (b.y - a.y)) + cells.lo.y,
                (cells.hi.z + (b.z - a.z)) + cells.lo.z};
    }
};

}  // namespace structmd
