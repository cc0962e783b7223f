// Compares structmd's CPU backend with LAMMPS on the force-field cases written by
// tests/reference/make_lammps_reference_forcefield.py (a Kremer-Grest FENE + WCA melt with bonded
// exclusions, molecules with harmonic bonds, angles and periodic dihedrals, a Kob-Andersen LJ mixture):
// forces, per-particle energies, the energy of every forceField entry and the virial tensor, in double
// and in single precision.
#include "physics_support.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace structmd_physics {
namespace {

struct ForceFieldCase {
    std::string name;
    std::string precision;
    double tolerance;
};

// Names the case in gtest's messages instead of dumping the struct's bytes.
void PrintTo(const ForceFieldCase& c, std::ostream* out) { *out << c.name << " " << c.precision; }

std::string data_path(const std::string& file) { return std::string(STRUCTMD_REFERENCE_DATA_DIR) + "/" + file; }

nlohmann::json read_reference(const std::string& case_name) {
    const std::string path = data_path(case_name + ".lammps.json");
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path);
    return nlohmann::json::parse(in);
}

std::vector<double> flatten_rows(const nlohmann::json& rows) {
    std::vector<double> flat;
    for (const auto& row : rows)
        for (const auto& value : row) flat.push_back(value.get<double>());
    return flat;
}

void report(const ForceFieldCase& c, const std::string& quantity, double deviation) {
    std::printf("[ deviation ] %s %s %s: %.3e (tolerance %.0e)\n", c.name.c_str(), c.precision.c_str(),
                quantity.c_str(), deviation, c.tolerance);
}

class LammpsForceField : public ::testing::TestWithParam<ForceFieldCase> {
protected:
    void SetUp() override {
        const ForceFieldCase& c = GetParam();
        m_reference = read_reference(c.name);
        structmd_sim* raw = nullptr;
        ASSERT_EQ(structmd_create(create_options("cpu", c.precision).c_str(), &raw), STRUCTMD_OK)
            << structmd_last_error(nullptr);
        m_sim.reset(raw);
        ASSERT_STRUCTMD_OK(sim(), structmd_load_file(sim(), data_path(c.name + ".json").c_str()));
        ASSERT_STRUCTMD_OK(sim(), structmd_get_num_particles(sim(), &m_n));
        ASSERT_EQ(m_n, m_reference.at("num_particles").get<std::int64_t>());
    }

    structmd_sim* sim() const { return m_sim.get(); }

    nlohmann::json m_reference;
    SimHandle m_sim;
    std::int64_t m_n = 0;
};

TEST_P(LammpsForceField, Forces) {
    std::vector<double> forces(3 * m_n);
    ASSERT_STRUCTMD_OK(sim(), structmd_get_forces(sim(), forces.data(), m_n));
    const double deviation = max_relative_deviation(forces, flatten_rows(m_reference.at("forces")));
    report(GetParam(), "forces", deviation);
    EXPECT_LT(deviation, GetParam().tolerance);
}

TEST_P(LammpsForceField, ParticleEnergies) {
    std::vector<double> energies(m_n);
    ASSERT_STRUCTMD_OK(sim(), structmd_get_particle_energies(sim(), energies.data(), m_n));
    const auto reference = m_reference.at("particle_energies").get<std::vector<double>>();
    const double deviation = max_relative_deviation(energies, reference);
    report(GetParam(), "particle energies", deviation);
    EXPECT_LT(deviation, GetParam().tolerance);
}

// "potential" and one value per forceField entry (pair, bonds, angles, dihedrals), each of which LAMMPS
// computed with its own style alone.
TEST_P(LammpsForceField, EnergyTerms) {
    for (const auto& [term, reference] : m_reference.at("energy").items()) {
        double energy = 0.0;
        ASSERT_STRUCTMD_OK(sim(), structmd_get_energy(sim(), term.c_str(), &energy));
        const double deviation = relative_deviation(energy, reference.get<double>());
        report(GetParam(), "energy " + term, deviation);
        EXPECT_LT(deviation, GetParam().tolerance) << term << ": " << energy << " vs LAMMPS " << reference;
    }
}

TEST_P(LammpsForceField, Virial) {
    std::array<double, 9> virial{};
    ASSERT_STRUCTMD_OK(sim(), structmd_get_virial(sim(), virial.data()));
    const std::vector<double> flat = flatten_rows(m_reference.at("virial"));
    std::array<double, 9> reference{};
    std::copy(flat.begin(), flat.end(), reference.begin());
    const double deviation = tensor_relative_deviation(virial, reference);
    report(GetParam(), "virial", deviation);
    EXPECT_LT(deviation, GetParam().tolerance);
}

// Double: the codes differ in summation order, minimum-image rounding and the acos/atan2 paths of the
// angle terms, a few ulps of the largest terms; 1e-9 is the brief's bound. Single: float rounding of
// positions (about 5e-7 of a coordinate near the box edge) magnified by the steepest pair forces at
// r = 0.8 sigma gives a few 1e-6 of the largest force, and of the molecules' LJ energy, a sum of terms
// of both signs.
INSTANTIATE_TEST_SUITE_P(Cases, LammpsForceField,
                         ::testing::Values(ForceFieldCase{"kg_melt", "double", 1e-9},
                                           ForceFieldCase{"kg_melt", "single", 1e-5},
                                           ForceFieldCase{"molecules", "double", 1e-9},
                                           ForceFieldCase{"molecules", "single", 1e-5},
                                           ForceFieldCase{"lj_mixture", "double", 1e-9},
                                           ForceFieldCase{"lj_mixture", "single", 1e-5}),
                         [](const ::testing::TestParamInfo<ForceFieldCase>& info) {
                             return info.param.name + "_" + info.param.precision;
                         });

}  // namespace
}  // namespace structmd_physics
