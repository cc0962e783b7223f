// Reading ["External","HelixBoundaries"] (tabulated_field.hpp): the helix
//   h(t) = (R cos t, eps R sin t, p t / (2 pi) - L_z / 2),  0 <= t < 2 pi nTurns,
// R = helixRadius, p = helixPitch, eps = +1 (right-handed) or -1, whose nTurns turns span the box
// height exactly, so that it continues across the periodic boundary; and on each grid cell's centre
// the energy U = K (d - helixInnerRadius)^2 / 2 where the distance d to the helix exceeds
// helixInnerRadius, else 0. UAMMD-structured takes d as the distance to the nearest of nPointsHelix
// points along the helix; here that point only starts Newton's method on the squared distance along
// t, so d is the distance to the curve itself and the field does not depend on the sampling.
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/tabulated_field.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;

namespace {

struct Helix {
    double radius, pitch, handedness, length[3];

    // The separation from the helix point at t to x, by minimum image, and its first two
    // derivatives along t.
    void separation(double t, const double x[3], double d[3], double dd[3], double ddd[3]) const {
        const double c = std::cos(t), s = std::sin(t), rate = pitch / (2.0 * M_PI);
        const double h[3] = {radius * c, handedness * radius * s, rate * t - 0.5 * length[2]};
        for (int a = 0; a < 3; ++a) {
            d[a] = x[a] - h[a];
            d[a] -= length[a] * std::round(d[a] / length[a]);
        }
        dd[0] = radius * s, dd[1] = -handedness * radius * c, dd[2] = -rate;  // d(x - h)/dt
        ddd[0] = radius * c, ddd[1] = handedness * radius * s, ddd[2] = 0.0;
    }

    double distance(const double x[3], int samples, double tMax) const {
        double d[3], dd[3], ddd[3];
        double best = 0.0, bestSquared = INFINITY;
        for (int k = 0; k < samples; ++k) {
            const double t = tMax * k / samples;
            separation(t, x, d, dd, ddd);
            const double squared = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (squared < bestSquared) bestSquared = squared, best = t;
        }
        // Newton on f(t) = |x - h(t)|^2 / 2: f' = d . d', f'' = |d'|^2 + d . d''.
        double t = best;
        for (int iteration = 0; iteration < 20; ++iteration) {
            separation(t, x, d, dd, ddd);
            const double slope = d[0] * dd[0] + d[1] * dd[1] + d[2] * dd[2];
            const double curvature = dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2] + d[0] * ddd[0] + d[1] * ddd[1];
            if (!(curvature > 0.0)) break;
            const double step = slope / curvature;
            t -= step;
            if (std::abs(step) < 1e-14 * (1.0 + std::abs(t))) break;
        }
        separation(t, x, d, dd, ddd);
        return std::min(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), std::sqrt(bestSquared));
    }
};

std::vector<Parameter> helix_parameters() {
    return {number("helixPitch", "length", Must::be_positive),
            number("helixRadius", "length", Must::be_positive),
            with_default(number("eps", "1"), 1.0),
            number("helixInnerRadius", "length", Must::be_non_negative),
            number("K", "energy/length^2", Must::be_non_negative),
            number("nTurns", "1", Must::be_positive_integer),
            number("nPointsHelix", "1", Must::be_positive_integer),
            number("nx", "1", Must::be_positive_integer),
            number("ny", "1", Must::be_positive_integer),
            number("nz", "1", Must::be_positive_integer)};
}

ForceFieldComponent configure(const ForceFieldComponent& c, const ComponentEntry& entry,
                              const SystemDescription& system) {
    const ParameterValues v = input::read_parameters(entry.node, c.parameters);
    const std::string at = entry.node.path() + ".parameters.";
    const double eps = v["eps"];
    if (eps != 1.0 && eps != -1.0)
        throw input_error(at + "eps", "expected 1 (a right-handed helix) or -1 (left-handed), got " + std::to_string(eps));
    const double box[3] = {system.box[0], system.box[1], system.box[2]};
    const double height = v["helixPitch"] * v["nTurns"];
    if (std::abs(height - box[2]) > 1e-9 * box[2])
        throw input_error(at + "helixPitch", "helixPitch x nTurns = " + std::to_string(height) +
                                                 " must be the box height " + std::to_string(box[2]) +
                                                 ", so that the helix continues across the boundary");
    if (v["helixRadius"] > 0.5 * std::min(box[0], box[1]))
        throw input_error(at + "helixRadius", "expected at most half the box's width, got " +
                                                  std::to_string(v["helixRadius"]));
    auto config = std::make_shared<TabulatedFieldConfig>();
    const char* const axes[3] = {"nx", "ny", "nz"};
    size_t cells = 1;
    for (int a = 0; a < 3; ++a) {
        config->n[a] = static_cast<int>(v[axes[a]]);
        cells *= static_cast<size_t>(config->n[a]);
    }
    if (cells > (size_t{1} << 24))
        throw input_error(at + "nx", "the grid has " + std::to_string(cells) + " cells, more than 2^24");
    const Helix helix{v["helixRadius"], v["helixPitch"], eps, {box[0], box[1], box[2]}};
    const double tMax = 2.0 * M_PI * v["nTurns"], inner = v["helixInnerRadius"], K = v["K"];
    const int samples = static_cast<int>(v["nPointsHelix"]);
    config->energy.resize(cells);
    for (int k = 0; k < config->n[2]; ++k)
        for (int j = 0; j < config->n[1]; ++j)
            for (int i = 0; i < config->n[0]; ++i) {
                const int index[3] = {i, j, k};
                double x[3];
                for (int a = 0; a < 3; ++a) x[a] = (index[a] + 0.5) * box[a] / config->n[a] - 0.5 * box[a];
                const double d = helix.distance(x, samples, tMax);
                config->energy[i + config->n[0] * (j + static_cast<size_t>(config->n[1]) * k)] =
                    d > inner ? 0.5 * K * (d - inner) * (d - inner) : 0.0;
            }
    config->lambdaSquared = true;
    ForceFieldComponent configured = c;
    configured.config = config;
    return configured;
}

}  // namespace

ForceFieldComponent HelixBoundariesComponent::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.parameters = helix_parameters();
    c.configure = [c](const ComponentEntry& entry, const SystemDescription& system) {
        return configure(c, entry, system);
    };
    return c;
}

}  // namespace structmd
