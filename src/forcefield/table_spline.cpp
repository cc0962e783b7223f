#include "forcefield/table_spline.hpp"

#include <cmath>

namespace structmd {

namespace {

// A slope this large asks for a natural end (zero second derivative), as LAMMPS's spline does.
constexpr double kNaturalSlope = 0.99e30;

// The four numbers per node that UniformSpline reads: energy, its second derivative, force, its
// second derivative.
TableNodes interleave(double x0, double delta, const std::vector<double>& e, const std::vector<double>& e2,
                      const std::vector<double>& f, const std::vector<double>& f2) {
    TableNodes t;
    t.x0 = x0;
    t.delta = delta;
    t.n = static_cast<int>(e.size());
    t.coefficients.reserve(4 * e.size());
    for (size_t i = 0; i < e.size(); ++i) t.coefficients.insert(t.coefficients.end(), {e[i], e2[i], f[i], f2[i]});
    return t;
}

// Slopes of the force at the ends: the table's own (FP, FPRIME) or those of its end segments.
void force_slopes(const TablePoints& t, double& low, double& high) {
    const size_t n = t.x.size();
    if (t.hasForceSlopes) {
        low = t.forceSlopeLow;
        high = t.forceSlopeHigh;
        return;
    }
    low = (t.force[1] - t.force[0]) / (t.x[1] - t.x[0]);
    high = (t.force[n - 1] - t.force[n - 2]) / (t.x[n - 1] - t.x[n - 2]);
}

// The splines through the table's own points: energy (end slopes -force) and force.
struct PointSplines {
    std::vector<double> e2, f2;
};

PointSplines spline_points(const TablePoints& t) {
    double low, high;
    force_slopes(t, low, high);
    return {spline_second_derivatives(t.x, t.energy, -t.force.front(), -t.force.back()),
            spline_second_derivatives(t.x, t.force, low, high)};
}

// bond and angle tables: n nodes evenly spaced in x over [lo, hi], resplined with the end slopes of
// the table (energy: -force at the nodes; force: as the points' spline).
TableNodes resample_linear(const TablePoints& t, int n, double lo, double hi) {
    const PointSplines s = spline_points(t);
    const double delta = (hi - lo) / (n - 1);
    std::vector<double> x(n), e(n), f(n);
    for (int i = 0; i < n; ++i) {
        x[i] = lo + i * delta;
        e[i] = spline_value(t.x, t.energy, s.e2, x[i]);
        f[i] = spline_value(t.x, t.force, s.f2, x[i]);
    }
    double low, high;
    force_slopes(t, low, high);
    return interleave(lo, delta, e, spline_second_derivatives(x, e, -f.front(), -f.back()), f,
                      spline_second_derivatives(x, f, low, high));
}

}  // namespace

// Solves the tridiagonal system lower[i] y[i-1] + diag[i] y[i] + upper[i] y[i+1] = rhs[i] (lower[0] and
// upper[n-1] unused) by forward elimination and back substitution.
std::vector<double> solve_tridiagonal(const std::vector<double>& lower, std::vector<double> diag,
                                      const std::vector<double>& upper, std::vector<double> rhs) {
    const size_t n = diag.size();
    for (size_t i = 1; i < n; ++i) {
        const double m = lower[i] / diag[i - 1];
        diag[i] -= m * upper[i - 1];
        rhs[i] -= m * rhs[i - 1];
    }
    std::vector<double> y(n);
    y[n - 1] = rhs[n - 1] / diag[n - 1];
    for (size_t i = n - 1; i-- > 0;) y[i] = (rhs[i] - upper[i] * y[i + 1]) / diag[i];
    return y;
}

std::vector<double> spline_second_derivatives(const std::vector<double>& x, const std::vector<double>& y, double yp1,
                                              double ypn) {
    // Continuity of the first derivative at each inner node; the given slope, or M = 0, at each end.
    const size_t n = x.size();
    std::vector<double> diag(n), upper(n), rhs(n), lower(n);
    const auto h = [&](size_t i) { return x[i + 1] - x[i]; };
    const auto slope = [&](size_t i) { return (y[i + 1] - y[i]) / h(i); };
    if (yp1 > kNaturalSlope) {
        diag[0] = 1.0, upper[0] = 0.0, rhs[0] = 0.0;
    } else {
        diag[0] = 2.0 * h(0), upper[0] = h(0), rhs[0] = 6.0 * (slope(0) - yp1);
    }
    for (size_t i = 1; i + 1 < n; ++i) {
        lower[i] = h(i - 1);
        diag[i] = 2.0 * (h(i - 1) + h(i));
        upper[i] = h(i);
        rhs[i] = 6.0 * (slope(i) - slope(i - 1));
    }
    if (ypn > kNaturalSlope) {
        lower[n - 1] = 0.0, diag[n - 1] = 1.0, rhs[n - 1] = 0.0;
    } else {
        lower[n - 1] = h(n - 2), diag[n - 1] = 2.0 * h(n - 2), rhs[n - 1] = 6.0 * (ypn - slope(n - 2));
    }
    return solve_tridiagonal(lower, diag, upper, rhs);
}

std::vector<double> cyclic_spline_second_derivatives(const std::vector<double>& x, const std::vector<double>& y,
                                                     double period) {
    // The same continuity at every node, the neighbours of the ends taken across the period; the
    // corners of the cyclic matrix are removed by the Sherman-Morrison formula.
    const size_t n = x.size();
    const auto h = [&](size_t i) { return i + 1 < n ? x[i + 1] - x[i] : x[0] + period - x[n - 1]; };
    const auto slope = [&](size_t i) { return (y[(i + 1) % n] - y[i]) / h(i); };
    std::vector<double> lower(n), diag(n), upper(n), rhs(n);
    for (size_t i = 0; i < n; ++i) {
        const size_t previous = (i + n - 1) % n;
        lower[i] = h(previous);
        diag[i] = 2.0 * (h(previous) + h(i));
        upper[i] = h(i);
        rhs[i] = 6.0 * (slope(i) - slope(previous));
    }
    const double corner0 = lower[0], cornerN = upper[n - 1];  // row 0's M_{n-1}, row n-1's M_0
    const double gamma = -diag[0];
    diag[0] -= gamma;
    diag[n - 1] -= corner0 * cornerN / gamma;
    const std::vector<double> solution = solve_tridiagonal(lower, diag, upper, rhs);
    std::vector<double> u(n, 0.0);
    u[0] = gamma;
    u[n - 1] = cornerN;
    const std::vector<double> z = solve_tridiagonal(lower, diag, upper, u);
    const double factor = (solution[0] + corner0 * solution[n - 1] / gamma) / (1.0 + z[0] + corner0 * z[n - 1] / gamma);
    std::vector<double> second(n);
    for (size_t i = 0; i < n; ++i) second[i] = solution[i] - factor * z[i];
    return second;
}

double cyclic_spline_value(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& y2,
                           double period, double xq) {
    const size_t n = x.size();
    size_t lo, hi;
    double xlo, xhi;
    if (xq < x[0] || xq >= x[n - 1]) {  // the interval across the period
        lo = n - 1, hi = 0;
        xlo = xq < x[0] ? x[n - 1] - period : x[n - 1];
        xhi = xq < x[0] ? x[0] : x[0] + period;
    } else {
        lo = 0, hi = n - 1;
        while (hi - lo > 1) {
            const size_t mid = (lo + hi) / 2;
            (x[mid] > xq ? hi : lo) = mid;
        }
        xlo = x[lo], xhi = x[hi];
    }
    const double h = xhi - xlo;
    const double a = (xhi - xq) / h;
    const double b = (xq - xlo) / h;
    return a * y[lo] + b * y[hi] + ((a * a * a - a) * y2[lo] + (b * b * b - b) * y2[hi]) * (h * h) / 6.0;
}

double spline_value(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& y2,
                    double xq) {
    size_t lo = 0, hi = x.size() - 1;
    while (hi - lo > 1) {
        const size_t mid = (lo + hi) / 2;
        if (x[mid] > xq)
            hi = mid;
        else
            lo = mid;
    }
    const double h = x[hi] - x[lo];
    const double a = (x[hi] - xq) / h;
    const double b = (xq - x[lo]) / h;
    return a * y[lo] + b * y[hi] + ((a * a * a - a) * y2[lo] + (b * b * b - b) * y2[hi]) * (h * h) / 6.0;
}

TableNodes lammps_pair_spline(const TablePoints& t, int n, double cutoff) {
    const PointSplines s = spline_points(t);
    const double inner = t.hasRange ? t.inner : t.x.front();
    const double innersq = inner * inner;
    const double delta = (cutoff * cutoff - innersq) / (n - 1);
    const auto force_at = [&](double r) { return spline_value(t.x, t.force, s.f2, r); };
    std::vector<double> rsq(n), e(n), f(n);
    for (int i = 0; i < n; ++i) {
        rsq[i] = innersq + i * delta;
        const double r = std::sqrt(rsq[i]);
        e[i] = spline_value(t.x, t.energy, s.e2, r);
        f[i] = force_at(r);
    }
    // Splines in r^2: dU/d(r^2) = -F / 2r at the ends. For F/r, d(F/r)/d(r^2) = (F'/r - F/r^2) / 2r
    // from the table's FPRIME slopes, else a secant over a tenth of a node spacing (the upper end
    // uses FPRIME only when the cutoff is the table's last point), as LAMMPS does.
    const double rInner = std::sqrt(innersq);
    const std::vector<double> e2 = spline_second_derivatives(rsq, e, -f[0] / (2.0 * rInner), -f[n - 1] / (2.0 * cutoff));
    const double secant = 0.1 * delta;
    double low, high;
    if (t.hasForceSlopes) {
        low = (t.forceSlopeLow / rInner - f[0] / innersq) / (2.0 * rInner);
    } else {
        const double r2 = std::sqrt(innersq + secant);
        low = (force_at(r2) / r2 - f[0] / rInner) / secant;
    }
    if (t.hasForceSlopes && cutoff == t.x.back()) {
        high = (t.forceSlopeHigh / cutoff - f[n - 1] / (cutoff * cutoff)) / (2.0 * cutoff);
    } else {
        const double r1 = std::sqrt(cutoff * cutoff - secant);
        high = (f[n - 1] / std::sqrt(cutoff * cutoff) - force_at(r1) / r1) / secant;
    }
    for (int i = 0; i < n; ++i) f[i] /= std::sqrt(rsq[i]);
    return interleave(innersq, delta, e, e2, f, spline_second_derivatives(rsq, f, low, high));
}

TableNodes lammps_bond_spline(const TablePoints& t, int n) { return resample_linear(t, n, t.x.front(), t.x.back()); }

TableNodes lammps_angle_spline(const TablePoints& t, int n) { return resample_linear(t, n, 0.0, M_PI); }

TableNodes lammps_dihedral_spline(const TablePoints& t, int n) {
    constexpr double period = 2.0 * M_PI;
    const bool withForce = !t.force.empty();
    const std::vector<double> e2file = cyclic_spline_second_derivatives(t.x, t.energy, period);
    const std::vector<double> f2file = withForce ? cyclic_spline_second_derivatives(t.x, t.force, period) : e2file;
    const double delta = period / n;
    std::vector<double> phi(n), e(n), f(n, 0.0);
    for (int i = 0; i < n; ++i) {
        phi[i] = i * delta;
        e[i] = cyclic_spline_value(t.x, t.energy, e2file, period, phi[i]);
        if (withForce) f[i] = cyclic_spline_value(t.x, t.force, f2file, period, phi[i]);
    }
    const std::vector<double> e2 = cyclic_spline_second_derivatives(phi, e, period);
    const std::vector<double> f2 = withForce ? cyclic_spline_second_derivatives(phi, f, period) : std::vector<double>(n, 0.0);
    // The node at 2 pi repeats the one at 0, so that every interval has its two ends in the table.
    TableNodes nodes = interleave(0.0, delta, e, e2, f, f2);
    nodes.coefficients.insert(nodes.coefficients.end(), nodes.coefficients.begin(), nodes.coefficients.begin() + 4);
    nodes.n = n + 1;
    nodes.forceFromEnergy = !withForce;
    return nodes;
}

}  // namespace structmd
