// registry.additions: components added at run time, the way a plugin will add them. A copy of the
// built-in force-field registry and of the CPU engine's factories gains ["Bond2","TestSpring"],
// implemented by the harmonic bond's functor; an input using it is read and built through the
// copies, and its energy and forces must equal those of the same bonds loaded as ["Bond2","Harmonic"].
// The built-in registries must not know the new name afterwards: adding to a copy changes no global
// state. The same for an integrator.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "cpu_harness.hpp"
#include "forcefield/factory_entries.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "input/description.hpp"
#include "integrators/integrator_factory_entries.hpp"
#include "integrators/read_integrators.hpp"
#include "integrators/velocity_verlet.hpp"
#include "registry_inputs.hpp"

namespace structmd::registry_test {
namespace {

const ComponentKey kTestSpring{"Bond2", "TestSpring"};
const ComponentKey kHarmonic{"Bond2", "Harmonic"};
const std::vector<double> kTimes = {0.0};

using Spring = RadialBond<HarmonicBond>;

// What the reader needs to know of the new bond, as the built-in list declares a bond (the reader's
// visitor in component_registry.cpp is not public, so its few lines are repeated here).
ForceFieldComponent test_spring_component() {
    ForceFieldComponent c;
    c.key = kTestSpring;
    c.kind = InteractionKind::bond;
    c.arity = Spring::arity;
    c.parameters = Spring::parameters();
    return c;
}

Registry<ForceFieldComponent> extended_registry() {
    Registry<ForceFieldComponent> registry = forcefield_registry();
    registry.add(test_spring_component());
    return registry;
}

// The engine's factories plus the new bond's, made by the engine's own visitor entry for a bond.
CpuFactories extended_factories() {
    CpuFactories factories = cpu_factories();
    FactoryEntries<CpuBackend, double, double> entries;
    entries.bond<Spring>(kTestSpring);
    for (const auto& factory : entries.registry.entries()) factories.add(factory);
    return factories;
}

// The harmonic bonds of the chain's minimal input, under another type.
std::string input_as(const ComponentKey& key) {
    const ForceFieldComponent* harmonic = forcefield_registry().find(kHarmonic);
    if (!harmonic) throw Error(STRUCTMD_ERR_INTERNAL, "no harmonic bond");
    Json entry = forcefield_entry(*harmonic);
    entry["type"] = Json::array({key.cls, key.subclass});
    return document_with(*harmonic, entry).dump();
}

TEST(RunTimeAdditions, ABondAddedToACopyComputesLikeTheComponentItReuses) {
    const Registry<ForceFieldComponent> registry = extended_registry();
    const CpuFactories factories = extended_factories();

    const Scene added = read_scene(input_as(kTestSpring), registry);
    ASSERT_EQ(added.spec.bonds.size(), 1u);
    EXPECT_EQ(added.spec.bonds[0].key, kTestSpring);
    const std::vector<double> viaAddition = evaluate(added, added.spec, kTimes, factories);

    const Scene builtin = read_scene(input_as(kHarmonic));
    const std::vector<double> viaHarmonic = evaluate(builtin, builtin.spec, kTimes);
    ASSERT_EQ(viaAddition.size(), viaHarmonic.size());
    EXPECT_NE(viaHarmonic[0], 0.0) << "the bonds of the test are not stretched";
    for (size_t k = 0; k < viaHarmonic.size(); ++k) EXPECT_EQ(viaAddition[k], viaHarmonic[k]) << "number " << k;
}

TEST(RunTimeAdditions, TheBuiltInRegistriesStayAsTheyWere) {
    const size_t before = forcefield_registry().entries().size();
    const size_t factoriesBefore = cpu_factories().entries().size();
    const Registry<ForceFieldComponent> registry = extended_registry();
    const CpuFactories factories = extended_factories();
    EXPECT_EQ(registry.entries().size(), before + 1);
    EXPECT_EQ(factories.entries().size(), factoriesBefore + 1);

    EXPECT_EQ(forcefield_registry().find(kTestSpring), nullptr);
    EXPECT_EQ(cpu_factories().find(kTestSpring), nullptr);
    EXPECT_EQ(forcefield_registry().entries().size(), before);
    EXPECT_EQ(cpu_factories().entries().size(), factoriesBefore);

    // The built-in reader rejects the name, suggesting what it knows, which does not include it.
    try {
        read_scene(input_as(kTestSpring));
        ADD_FAILURE() << "the built-in registry read a component only a copy knows";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), STRUCTMD_ERR_INPUT) << e.what();
        const std::string message = e.what();
        EXPECT_NE(message.find("unknown component"), std::string::npos) << message;
        const size_t known = message.find("nearest known components:");
        ASSERT_NE(known, std::string::npos) << message;
        EXPECT_EQ(message.find(kTestSpring.text(), known), std::string::npos) << message;
    }

    // A spec read with the extended registry cannot be built with the built-in factories.
    const Scene added = read_scene(input_as(kTestSpring), registry);
    try {
        evaluate(added, added.spec, kTimes);
        ADD_FAILURE() << "the built-in factories built a component only a copy knows";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), STRUCTMD_ERR_INTERNAL) << e.what();
        EXPECT_NE(std::string(e.what()).find(kTestSpring.text()), std::string::npos) << e.what();
    }
}

TEST(RunTimeAdditions, AnIntegratorAddedToACopyIsReadAndBuilt) {
    const ComponentKey key{"TestVerlet", "VelocityVerlet"};
    Registry<IntegratorComponent> registry = integrator_registry();
    const size_t before = integrator_registry().entries().size();
    registry.add({key, VelocityVerletInputs::parameters(), VelocityVerletInputs::minimiser,
                  VelocityVerletInputs::needsRadius, &VelocityVerletInputs::validate});
    IntegratorFactoryEntries<CpuBackend, double> entries;
    entries.integrator<VelocityVerlet, VelocityVerletInputs>(key);
    Registry<IntegratorFactory<CpuBackend, double>> factories = builtin_integrator_factories<CpuBackend, double>();
    for (const auto& factory : entries.registry.entries()) factories.add(factory);

    const Json stepper = {{"type", {key.cls, key.subclass}}, {"parameters", {{"timeStep", 0.001}}}};
    const input::ParsedDocument parsed = input::parse_document(document(Json::object(), stepper).dump());
    std::vector<ScheduleStage> schedule;
    std::vector<IntegratorSpec> specs;
    ASSERT_NO_THROW(specs = read_integrators(parsed.system, {}, schedule, registry));
    ASSERT_EQ(specs.size(), 1u);
    EXPECT_EQ(specs[0].key, key);
    EXPECT_EQ(specs[0].timeStep, 0.001);
    const CpuBackend backend(1);
    EXPECT_NE((make_integrator<CpuBackend, double>(backend, specs[0], nullptr, factories)), nullptr);

    EXPECT_EQ(integrator_registry().find(key), nullptr);
    EXPECT_EQ(integrator_registry().entries().size(), before);
    EXPECT_EQ((builtin_integrator_factories<CpuBackend, double>().find(key)), nullptr);
    try {
        read_integrators(parsed.system, {}, schedule);
        ADD_FAILURE() << "the built-in integrator registry read an integrator only a copy knows";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), STRUCTMD_ERR_INPUT) << e.what();
        EXPECT_NE(std::string(e.what()).find("unknown integrator"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace structmd::registry_test
