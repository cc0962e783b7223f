#pragma once
// Cubic splines of tabulated potentials, as LAMMPS's `table spline` styles build them.
//
// Host side (table_spline.cpp): the clamped cubic spline through (x_i, y_i) with given end slopes
// (the second derivatives y2_i of the interpolant; a slope > 0.99e30 makes that end natural), its
// value anywhere inside the nodes, and the three resamplings LAMMPS does before a run:
//   pair_style table spline N    N nodes evenly spaced in r^2 from the inner radius to the cutoff;
//                                 energy and force/r splined in r^2
//   bond_style table spline N    N nodes evenly spaced in r from the first to the last file point
//   angle_style table spline N   N nodes evenly spaced in theta over [0, pi]
//   dihedral_style table spline N   N nodes evenly spaced in phi over [0, 2 pi), with periodic
//                                 (cyclic) splines throughout and no end slopes
// Each first splines the file's points (energy with end slopes -force, force with the FP/FPRIME
// slopes or, without them, the slopes of its end segments), samples that spline at the N nodes, then
// splines the samples again; the engine evaluates only the second spline (UniformSpline).
//
// Device side: UniformSpline, the resampled table on an even grid, evaluated as
//   y(x) = a y_i + b y_{i+1} + ((a^3 - a) y2_i + (b^3 - b) y2_{i+1}) delta^2 / 6,
//   b = (x - x_i) / delta, a = 1 - b,
// for the energy and the force columns alike (the force column is its own spline, not the
// derivative of the energy's, as in LAMMPS).
#include <vector>

#include "core/hd.hpp"

namespace structmd {

// Second derivatives of the cubic spline through (x, y) with end slopes yp1, ypn.
std::vector<double> spline_second_derivatives(const std::vector<double>& x, const std::vector<double>& y, double yp1,
                                              double ypn);
// The periodic spline through (x, y) repeating every `period` (x ascending, spanning less than a
// period), and its value at xq in [x.back() - period, x.front() + period].
std::vector<double> cyclic_spline_second_derivatives(const std::vector<double>& x, const std::vector<double>& y,
                                                     double period);
double cyclic_spline_value(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& y2,
                           double period, double xq);
// The spline's value at xq (x ascending; bisection for the interval, extrapolating the end cubic
// outside the nodes).
double spline_value(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& y2,
                    double xq);

// A table as read from a file or an input: abscissae ascending (r, or theta in radians), energy, and
// force (-dU/dx), with the end slopes of the force if the table gives them (FP / FPRIME).
struct TablePoints {
    std::vector<double> x, energy, force;  // force empty: not given (dihedral NOF)
    bool hasForceSlopes = false;
    double forceSlopeLow = 0.0, forceSlopeHigh = 0.0;
    // pair tables with R/RSQ rlo rhi: the resampled table starts at rlo (not x[0]) and its default
    // cutoff is rhi (not x.back())
    bool hasRange = false;
    double inner = 0.0, outer = 0.0;
};

// The resampled table the engine evaluates: n nodes at x0 + i delta, in the layout of UniformSpline
// (e, e2, f, f2 for each node). For pair tables x is r^2 and f is force / r.
struct TableNodes {
    double x0 = 0.0, delta = 0.0;
    int n = 0;
    std::vector<double> coefficients;  // 4 per node
    bool forceFromEnergy = false;      // no force column: the force is -dU/dx of the energy's spline
};

TableNodes lammps_pair_spline(const TablePoints& t, int n, double cutoff);
TableNodes lammps_bond_spline(const TablePoints& t, int n);
TableNodes lammps_angle_spline(const TablePoints& t, int n);
TableNodes lammps_dihedral_spline(const TablePoints& t, int n);  // x in [0, 2 pi); n + 1 nodes, the last = the first

// The resampled table on the backend: nodes point to 4 values per node.
template <class R>
struct UniformSpline {
    const R* nodes = nullptr;
    R x0 = 0;
    R delta = 0;
    R invdelta = 0;
    R deltasq6 = 0;
    int n = 0;
};

template <class R>
UniformSpline<R> uniform_spline(const TableNodes& t, const R* nodes) {
    return {nodes, R(t.x0), R(t.delta), R(1.0 / t.delta), R(t.delta * t.delta / 6.0), t.n};
}

template <class R>
struct SplineSample {
    R energy;
    R force;
};

// Where x falls: its interval i (the last node's interval is extended to take x at, or rounded just
// past, the upper end) and the fractions a, b of the way to each end.
template <class R>
struct SplinePlace {
    const R* lo;
    R a, b;
};

template <class R>
SMD_HD SMD_INLINE SplinePlace<R> place_in_spline(const UniformSpline<R>& s, R x) {
    int i = static_cast<int>((x - s.x0) * s.invdelta);
    if (i > s.n - 2) i = s.n - 2;
    if (i < 0) i = 0;
    const R b = (x - (s.x0 + R(i) * s.delta)) * s.invdelta;
    return {s.nodes + 4 * i, R(1) - b, b};
}

// The table at x, for x0 <= x <= x0 + (n - 1) delta; the caller decides what lies outside.
template <class R>
SMD_HD SMD_INLINE SplineSample<R> evaluate_spline(const UniformSpline<R>& s, R x) {
    const SplinePlace<R> p = place_in_spline(s, x);
    const R* lo = p.lo;
    const R* hi = lo + 4;
    const R ca = p.a * p.a * p.a - p.a;
    const R cb = p.b * p.b * p.b - p.b;
    return {p.a * lo[0] + p.b * hi[0] + (ca * lo[1] + cb * hi[1]) * s.deltasq6,
            p.a * lo[2] + p.b * hi[2] + (ca * lo[3] + cb * hi[3]) * s.deltasq6};
}

// -dU/dx of the energy's spline at x (for tables without a force column).
template <class R>
SMD_HD SMD_INLINE R energy_spline_force(const UniformSpline<R>& s, R x) {
    const SplinePlace<R> p = place_in_spline(s, x);
    const R* lo = p.lo;
    const R* hi = lo + 4;
    return (lo[0] - hi[0]) * s.invdelta +
           ((R(3) * p.a * p.a - R(1)) * lo[1] - (R(3) * p.b * p.b - R(1)) * hi[1]) * s.delta / R(6);
}

}  // namespace structmd
