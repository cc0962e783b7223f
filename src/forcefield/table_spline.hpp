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
// The spline's value at xq (x ascending; bisection for the interval, extrapolating the end cubic
// outside the nodes).
double spline_value(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& y2,
                    double xq);

// A table as read from a file or an input: abscissae ascending (r, or theta in radians), energy, and
// force (-dU/dx), with the end slopes of the force if the table gives them (FP / FPRIME).
struct TablePoints {
    std::vector<double> x, energy, force;
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
};

TableNodes lammps_pair_spline(const TablePoints& t, int n, double cutoff);
TableNodes lammps_bond_spline(const TablePoints& t, int n);
TableNodes lammps_angle_spline(const TablePoints& t, int n);

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

// The table at x, for x0 <= x <= x0 + (n - 1) delta; the caller decides what lies outside. The last
// node's interval is extended to take x at (or rounded just past) the upper end.
template <class R>
SMD_HD SMD_INLINE SplineSample<R> evaluate_spline(const UniformSpline<R>& s, R x) {
    int i = static_cast<int>((x - s.x0) * s.invdelta);
    if (i > s.n - 2) i = s.n - 2;
    if (i < 0) i = 0;
    const R* lo = s.nodes + 4 * i;
    const R* hi = lo + 4;
    const R b = (x - (s.x0 + R(i) * s.delta)) * s.invdelta;
    const R a = R(1) - b;
    const R ca = a * a * a - a;
    const R cb = b * b * b - b;
    return {a * lo[0] + b * hi[0] + (ca * lo[1] + cb * hi[1]) * s.deltasq6,
            a * lo[2] + b * hi[2] + (ca * lo[3] + cb * hi[3]) * s.deltasq6};
}

}  // namespace structmd
