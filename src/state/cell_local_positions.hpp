#pragma once
// A neighbour list's positions in float, each relative to the centre of the cell where the list last
// binned it: what a mixed-precision pair kernel reads of a neighbour. Half the bytes of the double
// positions, gathered once per list entry, and a separation whose rounding is that of a cell's width
// (about 1e-7 of a few sigma), not of the box's: taken in float from absolute positions it would grow
// with the box (ulp(L / 2), 4e-6 at a million LJ particles).
//
// The cell's coordinates travel in w, packed as cx + bx (cy + by cz), an integer that a float holds
// exactly, with digits bx and by powers of two at least twice the cells along x and y: the difference
// of two codes then splits into the cells' differences by rounding alone, in float arithmetic at the
// GPU's full rate (the integer unpacking and conversions it replaces ran at a quarter of it). Two
// particles of a pair within the cutoff were in the same or adjacent cells at the build (within
// `reach` cells), so their separation is the difference of their local positions plus the
// difference of their cells, folded once across the periodic boundary: no minimum image of the box.
// Kept only where every axis is periodic and has more than 2 reach cells, and the codes fit in 24
// bits (verlet_list.hpp).
#include "core/box.hpp"
#include "core/real_limits.hpp"

namespace structmd {

template <class R>
struct CellLocalPositions {
    Real4<float>* local = nullptr;  // by slot; null: not kept
    Vec3<R> width{R(0), R(0), R(0)};  // a cell's edge along each axis
    // The width as the sum of two floats, hi + lo: the cells' distance, a small integer times it,
    // then keeps the width's double precision, whose float rounding (1e-7 of it) would otherwise be
    // the largest error of a separation. Kept here, where a GPU kernel reads them as operands of
    // its instructions without holding registers for them.
    Vec3<float> widthHi{0.0f, 0.0f, 0.0f}, widthLo{0.0f, 0.0f, 0.0f};
    // The same along y and z in the units of a list entry's offset bits (separation(a, b, entry)).
    Vec3<float> entryWidthHi{0.0f, 0.0f, 0.0f}, entryWidthLo{0.0f, 0.0f, 0.0f};
    Vec3<R> halfLength{R(0), R(0), R(0)};
    int bitsX = 1, bitsY = 1;  // the code's digits along x and y: bx = 2^bitsX, by = 2^bitsY
    // For separation(), as floats: the cells along each axis and their inverses, bx and bx by, and
    // their inverses (exact: powers of two).
    Vec3<float> cells{1.0f, 1.0f, 1.0f}, inverseCells{1.0f, 1.0f, 1.0f};
    float digitY = 2.0f, digitZ = 4.0f, inverseDigitY = 0.5f, inverseDigitZ = 0.25f;

    SMD_HD SMD_INLINE float pack(int cx, int cy, int cz) const {
        return static_cast<float>(cx | (cy | cz << bitsY) << bitsX);
    }
    SMD_HD SMD_INLINE int cell_x(int code) const { return code & ((1 << bitsX) - 1); }
    SMD_HD SMD_INLINE int cell_y(int code) const { return code >> bitsX & ((1 << bitsY) - 1); }
    SMD_HD SMD_INLINE int cell_z(int code) const { return code >> (bitsX + bitsY); }

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
        constexpr float kUnitY = 1 << kAxisBits, kUnitZ = 1 << 2 * kAxisBits;  // separation(a, b, entry)
        entryWidthHi = {widthHi.x, widthHi.y / kUnitY, widthHi.z / kUnitZ};
        entryWidthLo = {widthLo.x, widthLo.y / kUnitY, widthLo.z / kUnitZ};
    }
    // The digits for a grid of these cells (each difference of cells below half its digit).
    static int digit_bits(int cellsAlong) {
        int bits = 1;
        while ((1 << bits) < 2 * cellsAlong) ++bits;
        return bits;
    }
    // Whether the codes of such a grid, below bx by nz, are integers a float holds exactly.
    static bool codes_fit(int cellsX, int cellsY, int cellsZ) {
        return (1LL << (digit_bits(cellsX) + digit_bits(cellsY))) * cellsZ <= (1LL << 24);
    }
    void set_cells(int cellsX, int cellsY, int cellsZ) {
        bitsX = digit_bits(cellsX);
        bitsY = digit_bits(cellsY);
        cells = {static_cast<float>(cellsX), static_cast<float>(cellsY), static_cast<float>(cellsZ)};
        inverseCells = {1.0f / cells.x, 1.0f / cells.y, 1.0f / cells.z};
        digitY = static_cast<float>(1 << bitsX);
        digitZ = static_cast<float>(1 << (bitsX + bitsY));
        inverseDigitY = 1.0f / digitY;
        inverseDigitZ = 1.0f / digitZ;
    }
#endif

    // x rounded to the nearest integer (core/real_limits.hpp). No use here rounds a half: the
    // codes' quotients are exact, and a fold's at least 1/10 from one.
    static SMD_HD SMD_INLINE float nearest(float x) { return nearest_integer(x); }

    // b - a for two slots' local positions: their difference plus the cells' distance, each axis's
    // folded across the periodic boundary.
    // The codes' difference bx by dz + bx dy + dx, each |d| below half its digit, splits by
    // rounding: dz, then dy, then dx, all exact integers in float. A difference of cells n - 1
    // apart is the fold of one apart: d - n round(d / n) (n > 2 reach and reach <= 2, so a
    // neighbour's d / n is at least 1/10 from a half).
    SMD_HD SMD_INLINE Vec3<float> separation(const Real4<float>& a, const Real4<float>& b) const {
        const float code = b.w - a.w;
        const float dz = nearest(code * inverseDigitZ);
        const float rest = code - dz * digitZ;
        const float dy = nearest(rest * inverseDigitY);
        const float dx = rest - dy * digitY;
        const auto along = [](float d, float raw, float n, float inverseN, float hi, float lo) {
            const float c = raw - n * nearest(raw * inverseN);
            return (c * hi + d) + c * lo;  // c * hi exact: |c| <= 2
        };
        return {along(b.x - a.x, dx, cells.x, inverseCells.x, widthHi.x, widthLo.x),
                along(b.y - a.y, dy, cells.y, inverseCells.y, widthHi.y, widthLo.y),
                along(b.z - a.z, dz, cells.z, inverseCells.z, widthHi.z, widthLo.z)};
    }

    // A GPU list (NeighbourView::entryShift) writes each entry with the cells' offset of its pair
    // at the build, each axis's in [-2, 2] (the reach), stored plus 2 in three
    // bits below the slot (x lowest): separation(a, b, entry) then takes the cells' distance from the
    // entry as exact floats, three instructions an axis, where separation() above unpacks the codes
    // and folds them (sixteen in all). Both positions stay relative to the cells of that build, so
    // the offset holds until the next. Slots below 2^23.
    static constexpr int kAxisBits = 3, kOffsetBits = 3 * kAxisBits;
    static constexpr int64_t kMostEntrySlots = int64_t(1) << (32 - kOffsetBits);
    static SMD_HD SMD_INLINE int entry(int slot, int offsetBits) {
        return static_cast<int>(static_cast<unsigned>(slot) << kOffsetBits) | offsetBits;
    }
    // The offset bits of cells dx, dy, dz apart (each in [-2, 2]).
    static SMD_HD SMD_INLINE int offset_bits(int dx, int dy, int dz) {
        return (dx + 2) | (dy + 2) << kAxisBits | (dz + 2) << 2 * kAxisBits;
    }
    static SMD_HD SMD_INLINE int slot_of_entry(int entry) { return static_cast<int>(static_cast<unsigned>(entry) >> kOffsetBits); }

    // separation(a, b) for the pair of a list entry that carries its cells' offset: each axis's
    // bits, where they lie in the entry, become the mantissa of a float of exponent 23, whose units
    // are then the bits' own (1, 8 and 64 along x, y and z); less its bias (2^23 and the 2 added, in
    // those units) it is the offset in those units, an exact integer, and entryWidth along y and z
    // is the width divided by 8 and 64 to match (exactly: powers of two). Every sum rounds as
    // separation()'s.
    SMD_HD SMD_INLINE Vec3<float> separation(const Real4<float>& a, const Real4<float>& b, int entry) const {
        constexpr int kExponent23 = 0x4b000000;  // the bits of 2^23
        const auto along = [&](int axis) {
            const int shift = axis * kAxisBits;
            return float_of_bits((entry & ((1 << kAxisBits) - 1) << shift) | kExponent23) -
                   (0x1p23f + static_cast<float>(2 << shift));
        };
        const float cx = along(0), cy = along(1), cz = along(2);
        return {(cx * entryWidthHi.x + (b.x - a.x)) + cx * entryWidthLo.x,
                (cy * entryWidthHi.y + (b.y - a.y)) + cy * entryWidthLo.y,
                (cz * entryWidthHi.z + (b.z - a.z)) + cz * entryWidthLo.z};
    }

    // The cells' distance that separation() adds for cells a given number apart along each axis,
    // as its hi and lo parts (each product exact). A list build takes a run of cells' candidates
    // at one such shift along y and z (RowShift below) and unpacks no code but x's per candidate;
    // the pair kernel, whose neighbours' cells differ, keeps separation() above (with the shift as
    // a variable it spilled more registers).
    struct CellShift {
        Vec3<float> hi, lo;
    };
    SMD_HD SMD_INLINE CellShift shift(int cellsX, int cellsY, int cellsZ) const {
        const float x = static_cast<float>(cellsX), y = static_cast<float>(cellsY), z = static_cast<float>(cellsZ);
        return {{x * widthHi.x, y * widthHi.y, z * widthHi.z}, {x * widthLo.x, y * widthLo.y, z * widthLo.z}};
    }
    // The cells' distance over a run of cells consecutive along x (CellGrid::for_each_run_near):
    // along y and z the run's, along x each candidate's own, the difference of its code from
    // `origin` (the code of the cell at offset 0 in the run's row, which may lie outside the grid:
    // exact in float all the same). A list build then takes a whole run at one shift.
    struct RowShift {
        CellShift yz;
        float origin;
        // The cells from the slot's to b's along x, b in the run.
        SMD_HD SMD_INLINE float along_x(const Real4<float>& b) const { return b.w - origin; }
    };
    // For the run whose first cell, at x = firstX in row (py, pz), is dx cells from the slot's
    // (before the periodic wrap) and the row dy and dz.
    SMD_HD SMD_INLINE RowShift row_shift(int firstX, int py, int pz, int dx, int dy, int dz) const {
        return {shift(0, dy, dz), pack(firstX, py, pz) - static_cast<float>(dx)};
    }
    // separation(a, b) for b in the run of `row`, c its row.along_x(b): the same sums (c times a
    // width part is exact, |c| <= 2).
    SMD_HD SMD_INLINE Vec3<float> separation(const Real4<float>& a, const Real4<float>& b, const RowShift& row,
                                             float c) const {
        return {(c * widthHi.x + (b.x - a.x)) + c * widthLo.x, (row.yz.hi.y + (b.y - a.y)) + row.yz.lo.y,
                (row.yz.hi.z + (b.z - a.z)) + row.yz.lo.z};
    }
};

}  // namespace structmd
