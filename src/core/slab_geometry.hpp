#pragma once
// Slab domains along one axis of a periodic box, as the host (DomainsOverRanks) and the device (a
// domain's engine rebuilding its slots, simulation/domain_slots.hpp) both see them: which rank owns
// a coordinate, where an owned particle goes at a rebuild, and which faces of its slab it borders.
// One source, so that the two never disagree on a particle near a face.
#include <cmath>

#include "core/hd.hpp"

namespace structmd {

struct SlabGeometry {
    int axis = 0;         // the box axis the slabs are stacked along
    double length = 0.0;  // the box along it
    int ranks = 1;
    int rank = 0;         // whose slab this is
    double width = 0.0;   // of the ghost layer

    // The fractional coordinate of x, in [0, 1).
    SMD_HD SMD_INLINE double fraction(double x) const {
        const double f = x / length - floor(x / length);
        return f < 1.0 ? f : 0.0;
    }
    SMD_HD SMD_INLINE int slab_of(double x) const {
        const int slab = static_cast<int>(fraction(x) * ranks);
        return slab < ranks - 1 ? slab : ranks - 1;
    }
    // Where an owned particle at x goes: kStays, kUp (rank + 1), kDown (rank - 1) or kAstray
    // (farther: it crossed more than one slab since the last rebuild). With two ranks both
    // neighbours are the other rank: kUp.
    static constexpr int kStays = 0, kUp = 1, kDown = 2, kAstray = 3;
    SMD_HD SMD_INLINE int destination(double x) const {
        const int slab = slab_of(x);
        if (slab == rank) return kStays;
        if (slab == (rank + 1) % ranks) return kUp;
        if (slab == (rank + ranks - 1) % ranks) return kDown;
        return kAstray;
    }
    // The ghost links of a slab: to the rank above (0) and below (1); with two ranks one link, to
    // the other rank, which gets a particle near both faces once.
    SMD_HD SMD_INLINE int links() const { return ranks == 2 ? 1 : 2; }
    // Bit l set: a particle at x, in this slab, lies within the ghost width of the face link l sends
    // across.
    SMD_HD SMD_INLINE int borders(double x) const {
        const double at = fraction(x) * length;
        const double lower = length * rank / ranks, upper = length * (rank + 1) / ranks;
        const bool nearUpper = upper - at < width, nearLower = at - lower < width;
        if (ranks == 2) return nearUpper || nearLower ? 1 : 0;
        return (nearUpper ? 1 : 0) | (nearLower ? 2 : 0);
    }
    template <class V>
    SMD_HD SMD_INLINE double along(const V& position) const {
        return axis == 0 ? double(position.x) : axis == 1 ? double(position.y) : double(position.z);
    }
};

}  // namespace structmd
