// Compares structmd's CPU backend with LAMMPS on the configurations written by
// tests/reference/make_lammps_reference.py (an LJ liquid, LJ with bonds) and
// make_lammps_reference_forcefield.py (a Kremer-Grest FENE + WCA melt with bonded exclusions,
// molecules with bonds, angles and dihedrals, the same molecules as C-alpha chains with
// Best-Chen-Hummer angles and IDP_Fourier dihedrals, a Kob-Andersen mixture, semiflexible chains with
// harmonic bonds, Kratky-Porod angles and WCA, the walls of the Surface family): forces, per-particle
// energies, the energy of every forceField entry and the virial tensor, in double, mixed and single
// precision. LAMMPS's fix walls give neither per-atom energies nor a pair virial, so the Surface cases
// hold forces and entry energies only.
#include "physics_support.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace structmd_physics {
namespace {

struct ReferenceCase {
    std::string name;
    std::string precision;
    double tolerance;
};

std::string data_path(const std::string& file) { return std::string(STRUCTMD_REFERENCE_DATA_DIR) + "/" + file; }

nlohmann::json read_reference(const std::string& case_name) {
    std::ifstream in(data_path(case_name + ".lammps.json"));
    if (!in) throw std::runtime_error("cannot read " + data_path(case_name + ".lammps.json"));
    return nlohmann::json::parse(in);
}

std::vector<double> flatten_rows(const nlohmann::json& rows) {
    std::vector<double> flat;
    for (const auto& row : rows)
        for (const auto& value : row) flat.push_back(value.get<double>());
    return flat;
}

void report(const ReferenceCase& c, const std::string& quantity, double deviation) {
    std::printf("[ deviation ] %s %s %s: %.3e (tolerance %.0e)\n", c.name.c_str(), c.precision.c_str(),
                quantity.c_str(), deviation, c.tolerance);
}

class LammpsReference : public ::testing::TestWithParam<ReferenceCase> {
protected:
    void SetUp() override {
        const ReferenceCase& c = GetParam();
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

TEST_P(LammpsReference, Forces) {
    std::vector<double> forces(3 * m_n);
    ASSERT_STRUCTMD_OK(sim(), structmd_get_forces(sim(), forces.data(), m_n));
    const double deviation = max_relative_deviation(forces, flatten_rows(m_reference.at("forces")));
    report(GetParam(), "forces", deviation);
    EXPECT_LT(deviation, GetParam().tolerance);
}

TEST_P(LammpsReference, ParticleEnergies) {
    if (!m_reference.contains("particle_energies")) GTEST_SKIP() << "the reference has no per-particle energies";
    std::vector<double> energies(m_n);
    ASSERT_STRUCTMD_OK(sim(), structmd_get_particle_energies(sim(), energies.data(), m_n));
    const auto reference = m_reference.at("particle_energies").get<std::vector<double>>();
    const double deviation = max_relative_deviation(energies, reference);
    report(GetParam(), "particle energies", deviation);
    EXPECT_LT(deviation, GetParam().tolerance);
}

TEST_P(LammpsReference, EnergyTerms) {
    for (const auto& [term, reference] : m_reference.at("energy").items()) {
        double energy = 0.0;
        ASSERT_STRUCTMD_OK(sim(), structmd_get_energy(sim(), term.c_str(), &energy));
        const double deviation = relative_deviation(energy, reference.get<double>());
        report(GetParam(), "energy " + term, deviation);
        EXPECT_LT(deviation, GetParam().tolerance) << term << ": " << energy << " vs LAMMPS " << reference;
    }
}

TEST_P(LammpsReference, Virial) {
    if (!m_reference.contains("virial")) GTEST_SKIP() << "the reference has no virial";
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
// angle terms, a few ulps of the largest terms; the issue asks 1e-10 for the LJ cases and 1e-9 for the
// force-field cases. Single: float rounding of positions (about 5e-7 of a coordinate near the box
// edge) magnified by the steepest pair forces at r = 0.8 sigma gives a few 1e-6 of the largest force,
// and of the molecules' LJ energy, a sum of terms of both signs. Mixed: separations in float from
// cell-local positions (state/cell_local_positions.hpp), rounded by about 1e-7 of a cell's width
// whatever the box, and the pair potential in float.
// Surfaces: mixed precision evaluates external fields in double, so it agrees as double does; in
// single the 9-3 wall's energy (0.41) sums 40 terms from -0.52 to +1.11, on which float
// positions (rounded by 3e-7 near |z| = 5) and arithmetic leave about 2e-5 of it.
INSTANTIATE_TEST_SUITE_P(Cases, LammpsReference,
                         ::testing::Values(ReferenceCase{"lj_liquid", "double", 1e-10},
                                           ReferenceCase{"lj_liquid", "single", 1e-5},
                                           ReferenceCase{"lj_liquid", "mixed", 2e-6},
                                           ReferenceCase{"lj_bonds", "double", 1e-10},
                                           ReferenceCase{"lj_bonds", "single", 1e-5},
                                           ReferenceCase{"lj_bonds", "mixed", 2e-6},
                                           ReferenceCase{"kg_melt", "double", 1e-9},
                                           ReferenceCase{"kg_melt", "single", 1e-5},
                                           ReferenceCase{"kg_melt", "mixed", 2e-6},
                                           ReferenceCase{"molecules", "double", 1e-9},
                                           ReferenceCase{"molecules", "single", 1e-5},
                                           ReferenceCase{"molecules", "mixed", 2e-6},
                                           ReferenceCase{"lj_mixture", "double", 1e-9},
                                           ReferenceCase{"lj_mixture", "single", 1e-5},
                                           ReferenceCase{"lj_mixture", "mixed", 2e-6},
                                           ReferenceCase{"ca_chains", "double", 1e-9},
                                           ReferenceCase{"ca_chains", "single", 1e-5},
                                           ReferenceCase{"ca_chains", "mixed", 2e-6},
                                           ReferenceCase{"kp_chains", "double", 1e-9},
                                           ReferenceCase{"kp_chains", "single", 1e-5},
                                           ReferenceCase{"kp_chains", "mixed", 2e-6},
                                           ReferenceCase{"surfaces", "double", 1e-10},
                                           ReferenceCase{"surfaces", "single", 5e-5},
                                           ReferenceCase{"surfaces", "mixed", 1e-10},
                                           ReferenceCase{"plain_cylinder", "double", 1e-10},
                                           ReferenceCase{"plain_cylinder", "single", 1e-5},
                                           ReferenceCase{"plain_cylinder", "mixed", 1e-10}),
                         [](const ::testing::TestParamInfo<ReferenceCase>& info) {
                             return info.param.name + "_" + info.param.precision;
                         });

}  // namespace
}  // namespace structmd_physics
