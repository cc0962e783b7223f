// Checks F = -dU/dx: the engine's forces against a five-point central difference of its own potential
// energy, on small random systems whose interactions cross the periodic boundary, and on particles
// among the walls of the Surface family (with their per-type tables) and near a triangulated surface.
#include "physics_support.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace structmd_physics {
namespace {

// Five-point stencil: truncation error h^4 U^(5) / 30, about 1e-16 x 1e6 for LJ at r ~ 1; roundoff
// about 1.5 eps |U| / h, near 1e-10 here. Both are far below the 1e-6 tolerance of the brief, which
// a wrong sign, factor or missing image term exceeds by orders of magnitude.
constexpr double kStep = 1e-4;
constexpr double kTolerance = 1e-6;

struct SmallSystem {
    double box_length;
    std::vector<Vec3> positions;
    std::vector<std::string> types;
    std::string force_field;
    std::string units = "None";
    double temperature = 1.0;
    std::vector<std::string> acting;  // entries that must act on the configuration (nonzero energy)
};

const std::string kTwoTypeLennardJones =
    "\"nl\": {\"type\": [\"VerletConditionalListSet\", \"all\"], \"parameters\": {\"cutOffVerletFactor\": 1.1}},\n"
    "\"lj\": {\"type\": [\"NonBonded\", \"LennardJonesType1\"], \"parameters\": {\"cutOffFactor\": 2.5, \"condition\": \"all\"},\n"
    "       \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"],\n"
    "       \"data\": [[\"A\", \"A\", 1.0, 1.0], [\"A\", \"B\", 0.85, 1.1], [\"B\", \"B\", 0.7, 1.2]]}";

double sigma_of(const std::string& a, const std::string& b) {
    if (a != b) return 1.1;
    return a == "A" ? 1.0 : 1.2;
}

Vec3 wrapped(Vec3 r, double box_length) {
    for (double& x : r) x = minimum_image(x, box_length);
    return r;
}

double distance(const Vec3& a, const Vec3& b, double box_length) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double d = minimum_image(b[k] - a[k], box_length);
        s += d * d;
    }
    return std::sqrt(s);
}

// No pair closer than 0.95 sigma_ij, and none within 0.01 of its cutoff: the unshifted energy jumps
// there and a stencil straddling it would measure the jump, not the force.
bool acceptable(const SmallSystem& s, const Vec3& r, const std::string& type) {
    for (std::size_t j = 0; j < s.positions.size(); ++j) {
        const double sigma = sigma_of(type, s.types[j]);
        const double d = distance(r, s.positions[j], s.box_length);
        if (d < 0.95 * sigma || std::abs(d - 2.5 * sigma) < 0.01) return false;
    }
    return true;
}

// Pairs placed across each face and across a corner, then random particles.
SmallSystem lennard_jones_system() {
    SmallSystem s{7.0, {}, {}, kTwoTypeLennardJones};
    const std::vector<std::pair<Vec3, std::string>> across_boundary = {
        {{3.2, 0.3, -1.0}, "A"},  {{-2.9, 0.7, -0.6}, "B"},   // x face
        {{0.5, 3.3, 1.5}, "A"},   {{1.0, -2.9, 1.9}, "A"},    // y face
        {{-1.5, -1.2, 3.4}, "B"}, {{-1.2, -0.6, -2.6}, "B"},  // z face
        {{3.3, 3.2, 3.1}, "A"},   {{-3.0, -3.1, -3.2}, "B"},  // corner
    };
    for (const auto& [r, type] : across_boundary) {
        s.positions.push_back(r);
        s.types.push_back(type);
    }
    SplitMix64 rng(1234);
    while (s.positions.size() < 20) {
        const Vec3 r{rng.uniform(-3.5, 3.5), rng.uniform(-3.5, 3.5), rng.uniform(-3.5, 3.5)};
        const std::string type = rng.uniform(0.0, 1.0) < 0.5 ? "A" : "B";
        if (!acceptable(s, r, type)) continue;
        s.positions.push_back(r);
        s.types.push_back(type);
    }
    return s;
}

// Non-bonded neighbours of a new chain bead stay apart and off the LJ cutoff (see acceptable()).
bool clear_of_chain(const std::vector<Vec3>& chain, const Vec3& r, double box_length) {
    for (std::size_t j = 0; j + 1 < chain.size(); ++j) {
        const double d = distance(r, chain[j], box_length);
        if (d < 0.8 || std::abs(d - 2.5) < 0.01) return false;
    }
    return true;
}

// A random chain starting near a corner so that several bonds cross the boundary. Even bonds carry
// their own K and r0 (Bond2 Harmonic), odd bonds share them (HarmonicCommon_K_r0).
std::pair<std::vector<Vec3>, std::string> random_chain(std::size_t n, double box_length, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<Vec3> positions{{3.0, 2.9, 2.8}};
    std::string per_bond, common;
    while (positions.size() < n) {
        Vec3 direction{rng.normal(), rng.normal(), rng.normal()};
        const double norm = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
        const double length = rng.uniform(0.7, 1.4);
        Vec3 next = positions.back();
        for (int k = 0; k < 3; ++k) next[k] += length * direction[k] / norm;
        next = wrapped(next, box_length);
        if (!clear_of_chain(positions, next, box_length)) continue;
        positions.push_back(next);
        const std::string ids = std::to_string(positions.size() - 2) + ", " + std::to_string(positions.size() - 1);
        if (positions.size() % 2 == 0) {
            per_bond += std::string(per_bond.empty() ? "" : ", ") + "[" + ids + ", " + number(rng.uniform(50.0, 150.0)) +
                        ", " + number(rng.uniform(0.8, 1.2)) + "]";
        } else {
            common += std::string(common.empty() ? "" : ", ") + "[" + ids + "]";
        }
    }
    const std::string bonds =
        "\"bonds\": {\"type\": [\"Bond2\", \"Harmonic\"], \"labels\": [\"id_i\", \"id_j\", \"K\", \"r0\"], \"data\": [" +
        per_bond + "]},\n"
        "\"bondsCommon\": {\"type\": [\"Bond2\", \"HarmonicCommon_K_r0\"], \"parameters\": {\"K\": 80.0, \"r0\": 1.05},\n"
        "                \"labels\": [\"id_i\", \"id_j\"], \"data\": [" + common + "]}";
    return {positions, bonds};
}

SmallSystem harmonic_bond_system() {
    auto [positions, bonds] = random_chain(12, 6.0, 99);
    return SmallSystem{6.0, positions, std::vector<std::string>(positions.size(), "A"), bonds};
}

// Chain plus Lennard-Jones between all pairs, bonded ones included.
SmallSystem bonded_lennard_jones_system() {
    auto [positions, bonds] = random_chain(12, 7.0, 7);
    SmallSystem s{7.0, positions, std::vector<std::string>(positions.size(), "A"), kTwoTypeLennardJones + ",\n" + bonds};
    return s;
}

Vec3 separation(const Vec3& a, const Vec3& b, double box_length) {
    Vec3 d{};
    for (int k = 0; k < 3; ++k) d[k] = minimum_image(b[k] - a[k], box_length);
    return d;
}

double angle_at(const Vec3& a, const Vec3& b, const Vec3& c, double box_length) {
    const Vec3 u = separation(b, a, box_length), w = separation(b, c, box_length);
    double uw = 0.0, uu = 0.0, ww = 0.0;
    for (int k = 0; k < 3; ++k) {
        uw += u[k] * w[k];
        uu += u[k] * u[k];
        ww += w[k] * w[k];
    }
    return std::acos(uw / std::sqrt(uu * ww));
}

// A C-alpha-like chain (KcalMol_A units, 300 K) from a box corner, so that bonds cross the boundary,
// under every bonded term of issue 14: anisotropic springs along the chain, restraints between
// beads two apart (some stretched beyond maxDistance, some not), two particles tethered anisotropically
// to points across the boundary, Best-Chen-Hummer angles and IDP dihedrals. Each bead is drawn so
// that its angle stays 0.3 rad from 0 and pi, every restraint is 0.01 from its maxDistance and every
// separation component 0.01 from 0: no stencil straddles a kink of the restraint or a cusp of a spring.
SmallSystem issue14_bonded_system() {
    const double box = 6.0;
    SplitMix64 rng(1414);
    std::vector<Vec3> positions{{2.7, 2.8, 2.6}};
    const auto clear_of_zero = [](const Vec3& d) {
        return std::abs(d[0]) > 0.01 && std::abs(d[1]) > 0.01 && std::abs(d[2]) > 0.01;
    };
    while (positions.size() < 10) {
        Vec3 direction{rng.normal(), rng.normal(), rng.normal()};
        const double norm = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
        Vec3 next = positions.back();
        for (int k = 0; k < 3; ++k) next[k] += 3.8 / 4.0 * direction[k] / norm;  // 0.95
        next = wrapped(next, box);
        if (!clear_of_zero(separation(positions.back(), next, box))) continue;
        if (positions.size() >= 2) {
            const double theta = angle_at(positions[positions.size() - 2], positions.back(), next, box);
            if (theta < 0.3 || theta > 3.14159 - 0.3) continue;
            if (!clear_of_zero(separation(positions[positions.size() - 2], next, box))) continue;
        }
        positions.push_back(next);
    }
    std::string anisotropic, restraints, angles, dihedrals;
    const auto add = [](std::string& rows, const std::string& row) { rows += (rows.empty() ? "" : ", ") + row; };
    for (std::size_t i = 0; i + 1 < positions.size(); ++i)
        add(anisotropic, "[" + std::to_string(i) + ", " + std::to_string(i + 1) + ", [30.0, 45.0, 60.0], [0.3, 0.5, 0.2]]");
    for (std::size_t i = 0; i + 2 < positions.size(); ++i) {
        const Vec3 d = separation(positions[i], positions[i + 2], box);
        const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        // Alternately 0.2 shorter and 0.2 longer than the pair's distance (never within 0.01 of it).
        const double largest = r + (i % 2 == 0 ? -0.2 : 0.2);
        add(restraints, "[" + std::to_string(i) + ", " + std::to_string(i + 2) + ", 20.0, " + number(largest) + "]");
    }
    for (std::size_t i = 0; i + 2 < positions.size(); ++i)
        add(angles, "[" + std::to_string(i) + ", " + std::to_string(i + 1) + ", " + std::to_string(i + 2) + "]");
    for (std::size_t i = 0; i + 3 < positions.size(); ++i)
        add(dihedrals, "[" + std::to_string(i) + ", " + std::to_string(i + 1) + ", " + std::to_string(i + 2) + ", " +
                           std::to_string(i + 3) + "]");
    const std::string force_field =
        "\"anisotropic\": {\"type\": [\"Bond2\", \"HarmonicAnisotropic\"], \"labels\": [\"id_i\", \"id_j\", \"K\", \"r0\"],\n"
        "                \"data\": [" + anisotropic + "]},\n"
        "\"restraints\": {\"type\": [\"Bond2\", \"MaxDistanceRestraint\"], \"labels\": [\"id_i\", \"id_j\", \"K\", \"maxDistance\"],\n"
        "               \"data\": [" + restraints + "]},\n"
        "\"tethers\": {\"type\": [\"Bond1\", \"FixedHarmonicAnisotropic\"], \"labels\": [\"id_i\", \"K\", \"r0\", \"position\"],\n"
        "            \"data\": [[0, [5.0, 8.0, 3.0], [0.4, 0.0, 0.7], [-2.8, -2.9, 2.5]],\n"
        "                     [5, [6.0, 2.0, 9.0], [0.1, 0.6, 0.3], [0.3, -0.4, 0.5]]]},\n"
        "\"caAngles\": {\"type\": [\"Bond3\", \"BestChenHummerAngular\"], \"labels\": [\"id_i\", \"id_j\", \"id_k\"],\n"
        "             \"data\": [" + angles + "]},\n"
        "\"caDihedrals\": {\"type\": [\"Bond4\", \"IDP_Fourier\"], \"labels\": [\"id_i\", \"id_j\", \"id_k\", \"id_l\"],\n"
        "                \"data\": [" + dihedrals + "]}";
    SmallSystem s{box, positions, std::vector<std::string>(positions.size(), "A"), force_field};
    s.units = "KcalMol_A";
    s.temperature = 300.0;
    return s;
}

bool crosses_boundary(const Vec3& a, const Vec3& b, double box_length) {
    for (int k = 0; k < 3; ++k)
        if (std::abs(b[k] - a[k]) > 0.5 * box_length) return true;
    return false;
}

void check_forces_by_finite_differences(const std::string& label, const SmallSystem& s) {
    structmd_sim* raw = nullptr;
    ASSERT_EQ(structmd_create(create_options("cpu", "double").c_str(), &raw), STRUCTMD_OK) << structmd_last_error(nullptr);
    SimHandle handle(raw);
    structmd_sim* sim = handle.get();
    const std::string document =
        input_document(s.box_length, s.positions, s.types, {}, s.force_field, 0.005, s.units, s.temperature);
    ASSERT_STRUCTMD_OK(sim, structmd_load_string(sim, document.c_str()));

    const auto n = static_cast<std::int64_t>(s.positions.size());
    std::vector<double> xyz(3 * n), forces(3 * n), numerical(3 * n);
    ASSERT_STRUCTMD_OK(sim, structmd_get_positions(sim, xyz.data(), n));
    ASSERT_STRUCTMD_OK(sim, structmd_get_forces(sim, forces.data(), n));

    const double weights[4] = {1.0, -8.0, 8.0, -1.0};
    const double offsets[4] = {-2.0, -1.0, 1.0, 2.0};
    for (std::size_t c = 0; c < xyz.size(); ++c) {
        const double original = xyz[c];
        double derivative = 0.0;
        for (int k = 0; k < 4; ++k) {
            xyz[c] = original + offsets[k] * kStep;
            ASSERT_STRUCTMD_OK(sim, structmd_set_positions(sim, xyz.data(), n));
            double energy = 0.0;
            ASSERT_STRUCTMD_OK(sim, structmd_get_energy(sim, "potential", &energy));
            derivative += weights[k] * energy;
        }
        xyz[c] = original;
        numerical[c] = -derivative / (12.0 * kStep);
    }
    for (const std::string& term : s.acting) {
        double energy = 0.0;
        ASSERT_STRUCTMD_OK(sim, structmd_get_energy(sim, term.c_str(), &energy));
        EXPECT_NE(energy, 0.0) << term << " does not act on the configuration: the check would miss it";
    }
    const double deviation = max_relative_deviation(forces, numerical);
    std::printf("[ deviation ] finite differences %s: %.3e (max |F| %.3g, tolerance %.0e)\n", label.c_str(), deviation,
                max_abs(numerical), kTolerance);
    EXPECT_GT(max_abs(numerical), 1.0) << "the configuration exerts almost no force: the check would be empty";
    EXPECT_LT(deviation, kTolerance);
}

// ---- Surface walls ------------------------------------------------------------------------------

// One Surface entry: its component, the plane (or the plain cylinder's z0 and R) and per type
// (epsilon, sigma); a type with no row is not listed.
struct Wall {
    std::string name;
    std::string subclass;
    std::string parameters;
    std::vector<std::pair<std::string, std::pair<double, double>>> rows;
    double plane = 0.0;
};

std::string wall_entries(const std::vector<Wall>& walls) {
    std::string text;
    for (const Wall& w : walls) {
        std::string data;
        for (const auto& [type, values] : w.rows)
            data += std::string(data.empty() ? "" : ", ") + "[\"" + type + "\", " + number(values.first) + ", " +
                    number(values.second) + "]";
        text += std::string(text.empty() ? "" : ",\n") + "\"" + w.name + "\": {\"type\": [\"Surface\", \"" +
                w.subclass + "\"], \"parameters\": {" + w.parameters +
                "}, \"labels\": [\"name\", \"epsilon\", \"sigma\"], \"data\": [" + data + "]}";
    }
    return text;
}

const std::pair<double, double>* row_of(const Wall& w, const std::string& type) {
    for (const auto& row : w.rows)
        if (row.first == type) return &row.second;
    return nullptr;
}

// Every flat wall of the family, on particles of both types in a slab of a box of 12; each wall's
// table differs by type, the 9-3 wall lists A only (B must feel nothing from it), and the parabola's
// table carries the sigma column it ignores.
std::vector<Wall> flat_walls() {
    return {
        {"lj1", "SurfaceLennardJonesType1", "\"surfacePosition\": -5.2", {{"A", {1.0, 1.0}}, {"B", {0.6, 1.2}}}, -5.2},
        {"lj2", "SurfaceLennardJonesType2", "\"surfacePosition\": 5.2", {{"A", {0.8, 1.0}}, {"B", {1.2, 0.9}}}, 5.2},
        {"wca1", "SurfaceWCAType1", "\"surfacePosition\": -2.5", {{"A", {1.0, 0.8}}, {"B", {1.5, 0.7}}}, -2.5},
        {"wca2", "SurfaceWCAType2", "\"surfacePosition\": 2.5", {{"A", {1.0, 0.8}}, {"B", {0.5, 0.9}}}, 2.5},
        {"general1", "SurfaceGeneralLennardJonesType1", "\"surfacePosition\": -0.8",
         {{"A", {-0.7, 0.6}}, {"B", {1.0, 0.7}}}, -0.8},
        {"general2", "SurfaceGeneralLennardJonesType2", "\"surfacePosition\": 0.8",
         {{"A", {0.9, 0.6}}, {"B", {-0.4, 0.7}}}, 0.8},
        {"integrated", "SurfaceIntegratedLennardJonesType2", "\"surfacePosition\": -5.6", {{"A", {0.5, 0.8}}}, -5.6},
        {"anchor", "SurfaceAnchorage", "\"surfacePosition\": 1.6", {{"A", {3.0, 1.2}}, {"B", {2.0, 0.9}}}, 1.6},
        {"floor", "ParabolaSurface", "\"surfacePosition\": -1.5", {{"A", {4.0, 1.0}}, {"B", {2.5, 1.0}}}, -1.5},
    };
}

// Clear of every place where a wall is steep or not smooth enough for the stencil: each Lennard-Jones
// plane by 0.85 sigma, the WCA cutoffs, the edges of the anchorage well and the parabola's plane by
// 0.01 (the stencil spans 2e-4).
bool clear_of_walls(const std::vector<Wall>& walls, double z, const std::string& type) {
    for (const Wall& w : walls) {
        const auto* row = row_of(w, type);
        if (!row) continue;
        const double d = std::abs(z - w.plane), sigma = row->second;
        if (w.subclass == "ParabolaSurface") {
            if (d < 0.01) return false;
        } else if (w.subclass == "SurfaceAnchorage") {
            if (std::abs(d - sigma) < 0.01) return false;
        } else {
            if (d < 0.85 * sigma) return false;
            const bool type2 = w.subclass.back() == '2';
            if (std::abs(d - (type2 ? 1.0 : std::pow(2.0, 1.0 / 6.0)) * sigma) < 0.01) return false;
        }
    }
    return true;
}

SmallSystem flat_surfaces_system() {
    const std::vector<Wall> walls = flat_walls();
    SmallSystem s{12.0, {}, {}, wall_entries(walls)};
    for (const Wall& w : walls) s.acting.push_back(w.name);
    SplitMix64 rng(4242);
    // z within +-4.5: the wrapped coordinate never jumps across the box edge within reach of a wall.
    while (s.positions.size() < 40) {
        const Vec3 r{rng.uniform(-6.0, 6.0), rng.uniform(-6.0, 6.0), rng.uniform(-4.5, 4.5)};
        const std::string type = s.positions.size() % 2 ? "B" : "A";
        if (!clear_of_walls(walls, r[2], type)) continue;
        s.positions.push_back(r);
        s.types.push_back(type);
    }
    return s;
}

// The plain cylinder (z0 = -1, R = 3): particles near the plane beyond the well's mouth, near the
// well's wall below the plane and near the rim above the mouth, each between 0.85 sigma and the WCA
// range from the solid, and 0.01 clear of the region boundaries (z = z0 and rho = R), where the
// distance is only once differentiable.
SmallSystem plain_cylinder_system() {
    const double plane = -1.0, radius = 3.0;
    const Wall well{"well", "WCA_PlainCylinder", "\"plainPosition\": -1.0, \"cylinderRadius\": 3.0",
                    {{"A", {1.0, 0.8}}, {"B", {0.7, 1.0}}}};
    SmallSystem s{12.0, {}, {}, wall_entries({well})};
    s.acting = {"well"};
    SplitMix64 rng(77);
    while (s.positions.size() < 24) {
        const std::string type = s.positions.size() % 2 ? "B" : "A";
        const double sigma = row_of(well, type)->second;
        const double gap = rng.uniform(0.85, 1.1) * sigma;
        const double phi = rng.uniform(0.0, 2.0 * M_PI);
        double rho = 0.0, z = 0.0;
        switch (s.positions.size() % 3) {
            case 0: rho = rng.uniform(radius + 0.01, 5.5), z = plane + gap; break;     // the plane
            case 1: rho = radius - gap, z = rng.uniform(-5.5, plane - 0.01); break;     // the wall
            default: {                                                                  // the rim
                const double tilt = rng.uniform(0.05, 0.5 * M_PI - 0.05);
                rho = radius - gap * std::cos(tilt), z = plane + gap * std::sin(tilt);
            }
        }
        if (std::abs(rho - radius) < 0.01 || std::abs(z - plane) < 0.01 ||
            std::abs(gap - std::pow(2.0, 1.0 / 6.0) * sigma) < 0.01)
            continue;
        s.positions.push_back({rho * std::cos(phi), rho * std::sin(phi), z});
        s.types.push_back(type);
    }
    return s;
}

// A cube of half-edge 2 as a WCA_Polyhedron of 12 triangles: particles outside it near its faces,
// edges and corners, and inside it near one face. Inside, the distance is that to the nearest face, and
// where two faces are equally near it has a kink: inside particles keep 0.05 clear of those planes.
SmallSystem polyhedron_system() {
    const double h = 2.0;
    std::string vertices, faces;
    for (int k = 0; k < 8; ++k)
        vertices += std::string(k ? ", " : "") + vec_text({k & 1 ? h : -h, k & 2 ? h : -h, k & 4 ? h : -h});
    const int quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (const auto& q : quads)
        faces += std::string(faces.empty() ? "" : ", ") + "[" + std::to_string(q[0]) + ", " + std::to_string(q[1]) +
                 ", " + std::to_string(q[2]) + "], [" + std::to_string(q[0]) + ", " + std::to_string(q[3]) + ", " +
                 std::to_string(q[2]) + "]";
    const std::string entry = "\"cube\": {\"type\": [\"Surface\", \"WCA_Polyhedron\"], \"parameters\": {\"vertex\": [" +
                              vertices + "], \"faces\": [" + faces +
                              "]}, \"labels\": [\"name\", \"epsilon\", \"sigma\"], "
                              "\"data\": [[\"A\", 1.0, 0.8], [\"B\", 0.6, 1.0]]}";
    SmallSystem s{12.0, {}, {}, entry};
    s.acting = {"cube"};
    SplitMix64 rng(2718);
    while (s.positions.size() < 24) {
        const std::string type = s.positions.size() % 2 ? "B" : "A";
        const double sigma = type == "A" ? 0.8 : 1.0;
        const double reach = h + sigma;
        Vec3 r{rng.uniform(-reach, reach), rng.uniform(-reach, reach), rng.uniform(-reach, reach)};
        double outside = 0.0, inside[3];
        for (int k = 0; k < 3; ++k) {
            const double q = std::abs(r[k]) - h;
            outside += q > 0.0 ? q * q : 0.0;
            inside[k] = -q;
        }
        double gap = std::sqrt(outside);
        if (outside == 0.0) {
            std::sort(inside, inside + 3);
            if (inside[1] - inside[0] < 0.05) continue;
            gap = inside[0];
        }
        if (gap < 0.8 * sigma || gap > 1.1 * sigma) continue;
        s.positions.push_back(r);
        s.types.push_back(type);
    }
    return s;
}

TEST(FiniteDifference, LennardJonesTwoTypesAcrossBoundary) {
    const SmallSystem s = lennard_jones_system();
    int interacting_across = 0;
    for (std::size_t i = 0; i < s.positions.size(); ++i)
        for (std::size_t j = i + 1; j < s.positions.size(); ++j)
            if (crosses_boundary(s.positions[i], s.positions[j], s.box_length) &&
                distance(s.positions[i], s.positions[j], s.box_length) < 2.5 * sigma_of(s.types[i], s.types[j]))
                ++interacting_across;
    ASSERT_GE(interacting_across, 4);
    check_forces_by_finite_differences("lj two types", s);
}

TEST(FiniteDifference, HarmonicBondsAcrossBoundary) {
    const SmallSystem s = harmonic_bond_system();
    int bonds_across = 0;
    for (std::size_t i = 0; i + 1 < s.positions.size(); ++i)
        bonds_across += crosses_boundary(s.positions[i], s.positions[i + 1], s.box_length) ? 1 : 0;
    ASSERT_GE(bonds_across, 1);
    check_forces_by_finite_differences("harmonic bonds", s);
}

TEST(FiniteDifference, BondedLennardJonesChain) {
    const SmallSystem s = bonded_lennard_jones_system();
    int bonds_across = 0;
    for (std::size_t i = 0; i + 1 < s.positions.size(); ++i)
        bonds_across += crosses_boundary(s.positions[i], s.positions[i + 1], s.box_length) ? 1 : 0;
    ASSERT_GE(bonds_across, 1);
    for (std::size_t i = 0; i < s.positions.size(); ++i)
        for (std::size_t j = i + 1; j < s.positions.size(); ++j) {
            const double d = distance(s.positions[i], s.positions[j], s.box_length);
            ASSERT_GT(std::abs(d - 2.5), 0.01) << "pair " << i << "-" << j << " sits on the cutoff";
            ASSERT_GT(d, 0.65) << "pair " << i << "-" << j << " overlaps";
        }
    check_forces_by_finite_differences("lj + bonds", s);
}

// Every bonded term of issue 14 at once, through the reader, the bond kernels and the energy sum.
TEST(FiniteDifference, Issue14BondedTermsAcrossBoundary) {
    const SmallSystem s = issue14_bonded_system();
    int bonds_across = 0;
    for (std::size_t i = 0; i + 1 < s.positions.size(); ++i)
        bonds_across += crosses_boundary(s.positions[i], s.positions[i + 1], s.box_length) ? 1 : 0;
    ASSERT_GE(bonds_across, 1);
    check_forces_by_finite_differences("issue 14 bonded terms", s);
}

TEST(FiniteDifference, FlatSurfaceWallsWithPerTypeTables) {
    check_forces_by_finite_differences("surface walls", flat_surfaces_system());
}

TEST(FiniteDifference, PlainCylinderInEachRegion) {
    check_forces_by_finite_differences("plain cylinder", plain_cylinder_system());
}

TEST(FiniteDifference, PolyhedronInsideAndOutside) {
    check_forces_by_finite_differences("polyhedron", polyhedron_system());
}

}  // namespace
}  // namespace structmd_physics
