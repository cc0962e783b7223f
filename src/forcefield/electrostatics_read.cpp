// Reading ["LongRange","Electrostatics"]: its parameters, and the Ewald split, the pair term's cutoff
// and the mesh they imply (the rules are in docs/input-format.md).
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/periodic_box.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/electrostatics.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;

namespace {

std::vector<Parameter> electrostatics_parameters() {
    return {number("dielectricConstant", "1", Must::be_positive),
            number("gaussianWidth", "length", Must::be_non_negative),
            with_default(number("tolerance", "1", Must::be_positive), 1e-4),
            with_default(number("splitThreshold", "1/length", Must::be_non_negative), 0.0)};
}

// x where the pair term's force, relative to the Coulomb force k_e q_i q_j / r^2, falls to the
// tolerance: erfc(x) + 2x exp(-x^2) / sqrt(pi) = tolerance (< 1), x = r / 2s, by bisection (it falls
// monotonically).
double truncation_point(double tolerance) {
    const auto relativeForce = [](double x) { return std::erfc(x) + 2.0 * x * std::exp(-x * x) / std::sqrt(M_PI); };
    double lo = 0.0, hi = 30.0;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (relativeForce(mid) > tolerance ? lo : hi) = mid;
    }
    return hi;
}

// The smallest n >= at_least whose only prime factors are 2, 3 and 5 (fast for every FFT library).
int fft_friendly(int at_least) {
    for (int n = std::max(at_least, 1);; ++n) {
        int m = n;
        for (int f : {2, 3, 5})
            while (m % f == 0) m /= f;
        if (m == 1) return n;
    }
}

// The grid spacing h = s * kMeshSpacing * tolerance^(1/6): the B-splines' aliasing error falls as
// h^6 (their order); the constant is measured (tests/reference/electrostatics_reference.py prints the
// force error against the tolerance).
constexpr double kMeshSpacing = 3.0;

// The most grid points accepted (2^28: some GB of grid and spectrum), beyond which the input asks
// for more accuracy than the memory of a machine holds.
constexpr double kLargestMesh = 268435456.0;

// The least widening of the Gaussians (s / w) the automatic split makes.
constexpr double kWorthwhileSplit = 1.5;

std::string describe(double value) {
    std::ostringstream s;
    s.precision(17);
    s << value;
    return s.str();
}

ForceFieldComponent configure(ForceFieldComponent c, const ComponentEntry& entry, const SystemDescription& system) {
    const std::string path = entry.node.path() + ".parameters.";
    const ParameterValues v = input::read_parameters(entry.node, c.parameters);
    const double tolerance = v["tolerance"];
    if (!(tolerance < 1.0)) throw input_error(path + "tolerance", "expected a number below 1, got " + describe(tolerance));
    const double w = v["gaussianWidth"];
    const double split = v["splitThreshold"];
    if (std::set<int32_t>(system.batchId.begin(), system.batchId.end()).size() > 1)
        throw input_error(entry.node.path() + ".type",
                          "[\"LongRange\", \"Electrostatics\"] acts on the whole box: it cannot run with several "
                          "batches (batchId)");

    require_periodic_box({system.box[0], system.box[1], system.box[2]}, entry.node.path() + ".type",
                         "[\"LongRange\", \"Electrostatics\"] (Ewald sums over the periodic images)");
    const double box[3] = {system.box[0], system.box[1], system.box[2]};
    const double volume = box[0] * box[1] * box[2];
    const double halfBox = half_shortest_edge(box[0], box[1], box[2]);
    double totalCharge = 0.0;
    int64_t charged = 0;
    for (double q : system.charge) {
        totalCharge += q;
        if (q != 0.0) ++charged;
    }
    const double reach = 2.0 * truncation_point(tolerance);  // the pair term's cutoff over s

    // s: UAMMD's split xi gives s = sqrt(w^2 + 1/(4 xi^2)); without one, half the mean distance
    // between charges (a few tens of neighbours within the cutoff) where that is more than 1.5 w and
    // the box allows it, else w: a split that widens the Gaussians less saves too little of the mesh
    // to pay for a neighbour list.
    double s = w;
    if (split > 0.0) {
        s = std::sqrt(w * w + 0.25 / (split * split));
        if (!(reach * s < halfBox) && s > w)
            throw input_error(path + "splitThreshold",
                              "the pair term's cutoff " + describe(reach * s) + " is not shorter than half the box (" +
                                  describe(halfBox) + "): increase splitThreshold");
    } else {
        const double spacing = std::cbrt(volume / static_cast<double>(std::max<int64_t>(charged, 1)));
        const double wider = std::min(0.5 * spacing, 0.999 * halfBox / reach);
        s = wider > kWorthwhileSplit * w ? wider : w;
    }
    auto config = std::make_shared<ElectrostaticsConfig>();
    config->gaussianWidth = w;
    config->nearCutoff = s > w ? reach * s : 0.0;
    PmePlan& mesh = config->mesh;
    const double spacing = s * kMeshSpacing * std::pow(tolerance, 1.0 / 6.0);
    int* sizes[3] = {&mesh.grid.nx, &mesh.grid.ny, &mesh.grid.nz};
    double points[3];
    for (int d = 0; d < 3; ++d) points[d] = std::max(std::ceil(box[d] / spacing), 2.0 * kPmeOrder);
    if (!(points[0] * points[1] * points[2] <= kLargestMesh))
        throw input_error(path + "tolerance", "the mesh would need " + describe(points[0]) + " x " + describe(points[1]) +
                                                  " x " + describe(points[2]) + " points (at most 2^28): raise "
                                                  "tolerance, gaussianWidth or splitThreshold");
    for (int d = 0; d < 3; ++d) {
        mesh.box[d] = box[d];
        *sizes[d] = fft_friendly(static_cast<int>(points[d]));
    }
    mesh.prefactor = system.units.electricConversion / v["dielectricConstant"];
    mesh.farWidth = s;
    mesh.selfEnergy = mesh.prefactor / (2.0 * std::sqrt(M_PI) * s);
    mesh.backgroundEnergy = 2.0 * M_PI * mesh.prefactor * totalCharge * (s * s - w * w) / volume;
    mesh.totalCharge = totalCharge;
    c.config = config;
    return c;
}

}  // namespace

ForceFieldComponent Electrostatics::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.parameters = electrostatics_parameters();
    c.configure = [c](const ComponentEntry& entry, const SystemDescription& system) {
        return configure(c, entry, system);
    };
    return c;
}

}  // namespace structmd
