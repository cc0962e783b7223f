// registry.walk: every entry of the force-field and integrator registries loads, through the public
// C API (CPU backend, double precision), from a minimal input made from its schema alone, and
// computes something finite. A new component is walked as soon as it is registered: the list of
// tests is the registry itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "registry_inputs.hpp"
#include "structmd.h"

namespace structmd::registry_test {
namespace {

// A handle on the CPU backend in double precision, released at the end of the test.
class Handle {
public:
    Handle() {
        const char* options = R"({"backend": "cpu", "precision": "double", "threads": 1, "log": "quiet"})";
        if (structmd_create(options, &sim_) != STRUCTMD_OK) sim_ = nullptr;
    }
    ~Handle() { structmd_destroy(sim_); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    structmd_sim* get() const { return sim_; }
    std::string error() const { return structmd_last_error(sim_); }

private:
    structmd_sim* sim_ = nullptr;
};

std::vector<ComponentKey> forcefield_keys() { return schema_forcefield_keys(); }

std::vector<ComponentKey> integrator_keys() {
    std::vector<ComponentKey> keys;
    for (const IntegratorComponent& c : integrator_registry().entries()) keys.push_back(c.key);
    return keys;
}

// The walk below is only as good as the registry is full: every kind of interaction, every bond
// arity, and the integrators, are there to be walked.
TEST(RegistryWalk, TheRegistriesHoldEveryKind) {
    int pairs = 0, externals = 0;
    int bonds[5] = {0, 0, 0, 0, 0};
    for (const ForceFieldComponent& c : forcefield_registry().entries()) {
        if (c.kind == InteractionKind::pair) ++pairs;
        if (c.kind == InteractionKind::external) ++externals;
        if (c.kind == InteractionKind::bond) {
            ASSERT_TRUE(c.arity >= 1 && c.arity <= 4) << c.key.text() << " has arity " << c.arity;
            ++bonds[c.arity];
        }
    }
    EXPECT_GT(pairs, 0);
    EXPECT_GT(externals, 0);
    for (int arity = 1; arity <= 4; ++arity) EXPECT_GT(bonds[arity], 0) << "no bond of arity " << arity;
    EXPECT_FALSE(integrator_registry().entries().empty());
}

class ForceFieldWalk : public ::testing::TestWithParam<ComponentKey> {};

TEST_P(ForceFieldWalk, LoadsFromItsSchemaWithFiniteEnergyAndForces) {
    const ForceFieldComponent* c = forcefield_registry().find(GetParam());
    ASSERT_NE(c, nullptr);
    const std::string text = document_with(*c).dump();
    Handle sim;
    ASSERT_NE(sim.get(), nullptr) << structmd_last_error(nullptr);
    ASSERT_EQ(structmd_load_string(sim.get(), text.c_str()), STRUCTMD_OK) << sim.error() << "\ninput: " << text;

    double energy = NAN;
    ASSERT_EQ(structmd_get_energy(sim.get(), kEntryName, &energy), STRUCTMD_OK) << sim.error();
    EXPECT_TRUE(std::isfinite(energy)) << "energy term " << kEntryName << " = " << energy;
    double potential = NAN;
    ASSERT_EQ(structmd_get_energy(sim.get(), "potential", &potential), STRUCTMD_OK) << sim.error();
    EXPECT_EQ(potential, energy) << "the entry is the only term, so it is the whole potential energy";

    const int64_t n = static_cast<int64_t>(chain_positions().size());
    std::vector<double> forces(3 * n, NAN);
    ASSERT_EQ(structmd_get_forces(sim.get(), forces.data(), n), STRUCTMD_OK) << sim.error();
    std::vector<double> torques(3 * n, NAN);
    ASSERT_EQ(structmd_get_torques(sim.get(), torques.data(), n), STRUCTMD_OK) << sim.error();
    double largest = 0.0;
    for (const std::vector<double>* values : {&forces, &torques})
        for (double f : *values) {
            EXPECT_TRUE(std::isfinite(f)) << "a force or torque component is " << f;
            largest = std::max(largest, std::fabs(f));
        }
    // Every component pushes or turns some particle of this system: one that loads and does nothing is wrong.
    EXPECT_GT(largest, 0.0) << "no force or torque on any particle";
}

INSTANTIATE_TEST_SUITE_P(Registry, ForceFieldWalk, ::testing::ValuesIn(forcefield_keys()),
                         [](const auto& info) { return test_name(info.param); });

class IntegratorWalk : public ::testing::TestWithParam<ComponentKey> {};

// Each integrator moves the chain, held by stretched harmonic bonds, for a few steps (but ["None","None"]).
TEST_P(IntegratorWalk, LoadsFromItsSchemaAndSteps) {
    const IntegratorComponent* c = integrator_registry().find(GetParam());
    ASSERT_NE(c, nullptr);
    // Springs stretched by 0.08 to 0.21: forces of 8 to 21, well above the minimiser's
    // maxObjectiveForce (about 1), so that every integrator has something to do.
    Json forceField = Json::object();
    forceField["springs"] = Json{{"type", {"Bond2", "Harmonic"}},
                                 {"labels", {"id_i", "id_j", "K", "r0"}},
                                 {"data", Json::array({Json::array({0, 1, 100.0, 1.0}), Json::array({1, 2, 100.0, 1.0}),
                                                       Json::array({2, 3, 100.0, 1.0})})}};
    const std::string text = document(forceField, integrator_entry(*c)).dump();
    Handle sim;
    ASSERT_NE(sim.get(), nullptr) << structmd_last_error(nullptr);
    ASSERT_EQ(structmd_load_string(sim.get(), text.c_str()), STRUCTMD_OK) << sim.error() << "\ninput: " << text;
    ASSERT_EQ(structmd_step(sim.get(), 5), STRUCTMD_OK) << sim.error();
    int64_t step = -1;
    ASSERT_EQ(structmd_get_step(sim.get(), &step), STRUCTMD_OK);
    EXPECT_EQ(step, 5);
    const int64_t n = static_cast<int64_t>(chain_positions().size());
    std::vector<double> positions(3 * n, NAN);
    ASSERT_EQ(structmd_get_positions(sim.get(), positions.data(), n), STRUCTMD_OK) << sim.error();
    bool moved = false;
    for (int64_t i = 0; i < n; ++i)
        for (int a = 0; a < 3; ++a) {
            EXPECT_TRUE(std::isfinite(positions[3 * i + a]));
            moved = moved || positions[3 * i + a] != chain_positions()[i][a];
        }
    // A magnetic integrator may hold the particles fixed and turn only their moments.
    if (c->magnetic) {
        std::vector<double> moments(3 * n, NAN);
        ASSERT_EQ(structmd_get_magnetic_moments(sim.get(), moments.data(), n), STRUCTMD_OK) << sim.error();
        for (int64_t i = 0; i < n; ++i) {
            const Json& given = chain_magnetizations()[i];
            for (int a = 0; a < 3; ++a) {
                EXPECT_TRUE(std::isfinite(moments[3 * i + a]));
                moved = moved || std::fabs(moments[3 * i + a] - given[3].get<double>() * given[a].get<double>()) > 1e-12;
            }
        }
    }
    // ["None","None"] is the one integrator that moves nothing (its inputs measure a configuration).
    if (GetParam() == ComponentKey{"None", "None"})
        EXPECT_FALSE(moved) << "[\"None\", \"None\"] moved particles";
    else
        EXPECT_TRUE(moved) << "five steps left every particle and every moment where it was";
}

INSTANTIATE_TEST_SUITE_P(Registry, IntegratorWalk, ::testing::ValuesIn(integrator_keys()),
                         [](const auto& info) { return test_name(info.param); });

}  // namespace
}  // namespace structmd::registry_test
