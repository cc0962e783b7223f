// The tabulated components through the C API on the CPU: agreement with LAMMPS's `table spline`
// styles on the data of tests/reference/make_lammps_reference_tables.py (1e-8 relative in double),
// forces against central differences of the energy (across the periodic boundary too), inline tables
// against the same tables from a file, a pair closer than the table's inner radius reported as a
// numerical fault, and every bad table an input error naming its JSON path.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tabulated_support.hpp"

namespace structmd_tabulated {
namespace {

using structmd_physics::max_relative_deviation;
using structmd_physics::relative_deviation;
using structmd_physics::Vec3;

std::string data_path(const std::string& file) { return std::string(STRUCTMD_REFERENCE_DATA_DIR) + "/" + file; }

Json read_json(const std::string& path) {
    std::ifstream in(path);
    return Json::parse(in);
}

// The reference inputs name their table files relative to the data folder.
Json reference_input(const std::string& name) {
    Json doc = read_json(data_path(name + ".json"));
    for (auto& [entryName, entry] : doc["topology"]["forceField"].items()) {
        if (entry.contains("parameters") && entry["parameters"].contains("file"))
            entry["parameters"]["file"] = data_path(entry["parameters"]["file"]);
        if (entry.contains("labels")) {
            const auto& labels = entry["labels"];
            for (size_t c = 0; c < labels.size(); ++c)
                if (labels[c] == "file")
                    for (auto& row : entry["data"]) row[c] = data_path(row[c]);
        }
    }
    return doc;
}

std::vector<double> flatten(const Json& rows) {
    std::vector<double> flat;
    for (const auto& row : rows)
        for (const auto& v : row) flat.push_back(v.get<double>());
    return flat;
}

class LammpsTables : public ::testing::TestWithParam<std::string> {};

TEST_P(LammpsTables, ForcesAndEnergiesAgreeToOneInTenToTheEight) {
    const Json reference = read_json(data_path(GetParam() + ".lammps.json"));
    int status = -1;
    SimHandle sim = load(reference_input(GetParam()), &status);
    ASSERT_EQ(status, STRUCTMD_OK) << structmd_last_error(sim.get());
    const int64_t n = reference["num_particles"].get<int64_t>();
    const double forceDeviation = max_relative_deviation(forces(sim.get(), n), flatten(reference["forces"]));
    std::vector<double> energies(n);
    ASSERT_EQ(structmd_get_particle_energies(sim.get(), energies.data(), n), STRUCTMD_OK);
    const double particleDeviation =
        max_relative_deviation(energies, reference["particle_energies"].get<std::vector<double>>());
    const double energyDeviation = relative_deviation(potential(sim.get()), reference["energy"].get<double>());
    std::printf("[ deviation ] %s against LAMMPS: forces %.2e, particle energies %.2e, energy %.2e\n",
                GetParam().c_str(), forceDeviation, particleDeviation, energyDeviation);
    EXPECT_LT(forceDeviation, 1e-8);
    EXPECT_LT(particleDeviation, 1e-8);
    EXPECT_LT(energyDeviation, 1e-8);
}

INSTANTIATE_TEST_SUITE_P(Reference, LammpsTables, ::testing::Values("table_pair", "table_bonds", "table_dihedrals"));

// ---- finite differences -------------------------------------------------------------------------

// A fine LJ table (energy and force are separate splines, so -dU/dr of the energy spline matches the
// force spline only to the interpolation error).
Json fine_pair_entry() {
    const Points p = sample(lennard_jones, 0.8, 2.5, 2000);
    return {{"type", {"NonBonded", "Tabulated"}},
            {"parameters", {{"condition", "all"}, {"N", 4000}}},
            {"labels", {"name_i", "name_j", "r", "energy", "force"}},
            {"data", {{"A", "A", p.x, p.energy, p.force}}}};
}

// Particles near the faces of a box of 7, pairs across the boundary among them.
std::vector<Vec3> boundary_cluster() {
    return {{3.2, 0.1, 0.0}, {-3.1, 0.5, 0.3}, {2.6, -0.4, 0.6}, {-3.3, -0.6, -0.7}, {0.2, 3.3, -3.2}, {0.5, -3.0, 3.3}};
}

TEST(TabulatedFiniteDifference, PairForcesAreMinusTheEnergyGradientAcrossTheBoundary) {
    const std::vector<Vec3> x = boundary_cluster();
    const double deviation = gradient_deviation(7.0, x, {{"nl", neighbour_list()}, {"lj", fine_pair_entry()}});
    std::printf("[ deviation ] pair table against central differences: %.2e\n", deviation);
    EXPECT_LT(deviation, 1e-6);
}

TEST(TabulatedFiniteDifference, BondAndAngleForcesAreMinusTheEnergyGradientAcrossTheBoundary) {
    const std::vector<Vec3> x = {{2.7, 0.1, 0.0}, {-2.9, 0.4, 0.3}, {-2.3, 1.2, 0.2}, {-2.6, 1.9, -0.5}};
    const Points bond = sample(harmonic_bond, 0.5, 1.6, 2000);
    const Points angle = sample(harmonic_angle, 0.0, M_PI, 2000);
    const Json ff = {{"bonds", {{"type", {"Bond2", "Tabulated"}},
                                {"parameters", {{"N", 4000}, {"r", bond.x}, {"energy", bond.energy}, {"force", bond.force}}},
                                {"labels", {"id_i", "id_j"}}, {"data", {{0, 1}, {1, 2}, {2, 3}}}}},
                     {"angles", {{"type", {"Bond3", "Tabulated"}},
                                 {"parameters", {{"N", 4000}, {"theta", angle.x}, {"energy", angle.energy}, {"force", angle.force}}},
                                 {"labels", {"id_i", "id_j", "id_k"}}, {"data", {{0, 1, 2}, {1, 2, 3}}}}}};
    const double deviation = gradient_deviation(6.0, x, ff);
    std::printf("[ deviation ] bond and angle tables against central differences: %.2e\n", deviation);
    EXPECT_LT(deviation, 1e-6);
}

// A dihedral table with forces (periodic in phi, given on [-pi, pi)) and one without (NOF: the force is
// the derivative of the energy's spline), over a chain across the boundary.
TEST(TabulatedFiniteDifference, DihedralForcesAreMinusTheEnergyGradientAcrossTheBoundary) {
    const std::vector<Vec3> x = {{2.7, 0.1, 0.0}, {-2.9, 0.4, 0.3}, {-2.3, 1.2, 0.2}, {-2.6, 1.9, -0.5}, {-1.8, 2.5, -0.9}};
    const Points withForce = sample([](double phi) { return Sample{1.5 * (1 + std::cos(2 * phi - 0.5)), 3.0 * std::sin(2 * phi - 0.5)}; },
                                    -M_PI, M_PI - 2 * M_PI / 1000, 1000);
    const Points energyOnly = sample([](double phi) { return Sample{0.7 * (1 + std::cos(phi + 0.4)), 0.0}; }, 0.0,
                                     2 * M_PI - 2 * M_PI / 1000, 1000);
    const Json ff = {{"d1", {{"type", {"Bond4", "Tabulated"}},
                             {"parameters", {{"N", 2000}, {"phi", withForce.x}, {"energy", withForce.energy}, {"force", withForce.force}}},
                             {"labels", {"id_i", "id_j", "id_k", "id_l"}}, {"data", {{0, 1, 2, 3}}}}},
                     {"d2", {{"type", {"Bond4", "Tabulated"}},
                             {"parameters", {{"N", 2000}, {"phi", energyOnly.x}, {"energy", energyOnly.energy}}},
                             {"labels", {"id_i", "id_j", "id_k", "id_l"}}, {"data", {{1, 2, 3, 4}}}}}};
    const double deviation = gradient_deviation(6.0, x, ff);
    std::printf("[ deviation ] dihedral tables against central differences: %.2e\n", deviation);
    EXPECT_LT(deviation, 1e-6);
}

// ---- inline tables equal the same tables from a file ----------------------------------------------

std::vector<double> forces_of(const Json& doc, int64_t n) {
    int status = -1;
    SimHandle sim = load(doc, &status);
    EXPECT_EQ(status, STRUCTMD_OK) << structmd_last_error(sim.get());
    std::vector<double> f = forces(sim.get(), n);
    f.push_back(potential(sim.get()));
    return f;
}

TEST(TabulatedInline, PairTableEqualsTheSameFile) {
    const Points p = sample(lennard_jones, 0.8, 2.5, 151);
    const std::string file = write_table_file("inline_pair.table", "LJ", p);
    const std::vector<Vec3> x = boundary_cluster();
    const auto entry = [](const Json& labels, const Json& row) {
        return Json{{"type", {"NonBonded", "Tabulated"}}, {"parameters", {{"condition", "all"}, {"N", 500}}},
                    {"labels", labels}, {"data", {row}}};
    };
    const std::vector<std::string> types(x.size(), "A");
    const auto given = forces_of(document(7.0, x, types, {{"nl", neighbour_list()},
                                                           {"t", entry({"name_i", "name_j", "r", "energy", "force"},
                                                                       {"A", "A", p.x, p.energy, p.force})}}), 6);
    const auto fromFile = forces_of(document(7.0, x, types, {{"nl", neighbour_list()},
                                                              {"t", entry({"name_i", "name_j", "file", "keyword"},
                                                                          {"A", "A", file, "LJ"})}}), 6);
    EXPECT_EQ(given, fromFile);  // the same numbers through the same code: equal to the bit
}

TEST(TabulatedInline, BondAndAngleTablesEqualTheSameFiles) {
    const Points bond = sample(harmonic_bond, 0.5, 1.6, 111);
    const Points angle = sample(harmonic_angle, 0.0, M_PI, 181);
    const std::string bondFile = write_table_file("inline_bond.table", "B", bond);
    const std::string angleFile = write_table_file("inline_angle.table", "A", angle, 180.0 / M_PI);  // degrees
    const std::vector<Vec3> x = {{2.7, 0.1, 0.0}, {-2.9, 0.4, 0.3}, {-2.3, 1.2, 0.2}};
    const auto ff = [](const Json& bondTable, const Json& angleTable) {
        return Json{{"b", {{"type", {"Bond2", "Tabulated"}}, {"parameters", bondTable}, {"labels", {"id_i", "id_j"}},
                           {"data", {{0, 1}, {1, 2}}}}},
                    {"a", {{"type", {"Bond3", "Tabulated"}}, {"parameters", angleTable},
                           {"labels", {"id_i", "id_j", "id_k"}}, {"data", {{0, 1, 2}}}}}};
    };
    const auto given = forces_of(
        document(6.0, x, {"A", "A", "A"},
                 ff({{"N", 300}, {"r", bond.x}, {"energy", bond.energy}, {"force", bond.force}},
                    {{"N", 300}, {"theta", angle.x}, {"energy", angle.energy}, {"force", angle.force}})), 3);
    const auto fromFile = forces_of(document(6.0, x, {"A", "A", "A"},
                                             ff({{"N", 300}, {"file", bondFile}, {"keyword", "B"}},
                                                {{"N", 300}, {"file", angleFile}, {"keyword", "A"}})), 3);
    // The angle file is in degrees: equal up to the rounding of the conversion.
    EXPECT_LT(max_relative_deviation(fromFile, given), 1e-12);
}

TEST(TabulatedInline, DihedralTableEqualsTheSameFileInDegrees) {
    const Points p = sample([](double phi) { return Sample{1 + std::cos(3 * phi), 3 * std::sin(3 * phi)}; }, -M_PI,
                            M_PI - M_PI / 36, 72);
    const std::string file = write_table_file("inline_dihedral.table", "D", p, 180.0 / M_PI);  // degrees, the default
    const std::vector<Vec3> x = {{2.7, 0.1, 0.0}, {-2.9, 0.4, 0.3}, {-2.3, 1.2, 0.2}, {-2.6, 1.9, -0.5}};
    const auto ff = [](const Json& table) {
        return Json{{"d", {{"type", {"Bond4", "Tabulated"}}, {"parameters", table},
                           {"labels", {"id_i", "id_j", "id_k", "id_l"}}, {"data", {{0, 1, 2, 3}}}}}};
    };
    const auto given = forces_of(document(6.0, x, {"A", "A", "A", "A"},
                                          ff({{"N", 360}, {"phi", p.x}, {"energy", p.energy}, {"force", p.force}})), 4);
    const auto fromFile =
        forces_of(document(6.0, x, {"A", "A", "A", "A"}, ff({{"N", 360}, {"file", file}, {"keyword", "D"}})), 4);
    EXPECT_LT(max_relative_deviation(fromFile, given), 1e-12);
}

// ---- outside the table at run time ----------------------------------------------------------------

TEST(TabulatedRange, APairInsideTheInnerRadiusIsANumericalFaultNamingTheParticle) {
    const Points p = sample(lennard_jones, 0.8, 2.5, 100);
    const Json entry = {{"type", {"NonBonded", "Tabulated"}}, {"parameters", {{"condition", "all"}, {"N", 200}}},
                        {"labels", {"name_i", "name_j", "r", "energy", "force"}},
                        {"data", {{"A", "A", p.x, p.energy, p.force}}}};
    int status = -1;
    SimHandle sim = load(document(8.0, {{0, 0, 0}, {0.7, 0, 0}, {3, 3, 3}}, {"A", "A", "A"},
                                  {{"nl", neighbour_list()}, {"t", entry}}), &status);
    ASSERT_EQ(status, STRUCTMD_OK) << structmd_last_error(sim.get());
    std::vector<double> f(9);
    EXPECT_EQ(structmd_get_forces(sim.get(), f.data(), 3), STRUCTMD_ERR_NUMERICAL);
    EXPECT_EQ(structmd_step(sim.get(), 1), STRUCTMD_ERR_NUMERICAL);
    const std::string message = structmd_last_error(sim.get());
    EXPECT_NE(message.find("particle id 0"), std::string::npos) << message;
    EXPECT_NE(message.find("step 1"), std::string::npos) << message;
}

TEST(TabulatedRange, ABondOutsideItsTableIsANumericalFault) {
    const Points bond = sample(harmonic_bond, 0.5, 1.6, 50);
    const Json ff = {{"b", {{"type", {"Bond2", "Tabulated"}},
                            {"parameters", {{"N", 100}, {"r", bond.x}, {"energy", bond.energy}, {"force", bond.force}}},
                            {"labels", {"id_i", "id_j"}}, {"data", {{0, 1}}}}}};
    int status = -1;
    SimHandle sim = load(document(8.0, {{0, 0, 0}, {1.7, 0, 0}}, {"A", "A"}, ff), &status);
    ASSERT_EQ(status, STRUCTMD_OK) << structmd_last_error(sim.get());
    EXPECT_EQ(structmd_step(sim.get(), 1), STRUCTMD_ERR_NUMERICAL);
}

}  // namespace
}  // namespace structmd_tabulated
