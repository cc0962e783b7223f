// The time step an integrator steps with (input/time_step.hpp), the one rule the integrators, AFM's
// chip and the trajectory writers share: an integrator's own timeStep overrides global.fundamental's,
// and the first time step is that of the first integrator scheduled to run steps.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "input/description.hpp"
#include "input/time_step.hpp"

namespace structmd::input {
namespace {

using nlohmann::json;

constexpr double kGlobalTimeStep = 0.01;
constexpr double kOwnTimeStep = 0.002;

// "own" gives its time step; "inherits" takes global.fundamental's. The schedule runs "inherits" first.
json document() {
    return json::parse(R"({
      "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "time step"}}},
      "global": {
        "types": {"type": ["Types", "Basic"], "labels": ["name", "radius", "mass", "charge"], "data": [["A", 0.5, 1, 0]]},
        "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[10, 10, 10], 1]]},
        "fundamental": {"type": ["Fundamental", "Time"], "parameters": {"timeStep": 0.01}}
      },
      "state": {"labels": ["id", "position"], "data": [[0, [0, 0, 0]]]},
      "topology": {"structure": {"labels": ["id", "type"], "data": [[0, "A"]]}},
      "integrator": {
        "own": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.002}},
        "inherits": {"type": ["Verlet", "VelocityVerlet"]},
        "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                     "data": [[1, "inherits", 10], [2, "own", 10]]}
      }
    })");
}

const ComponentEntry& integrator(const SystemDescription& system, const std::string& name) {
    for (const ComponentEntry& entry : system.integrators)
        if (entry.name == name) return entry;
    throw std::runtime_error("no integrator " + name);
}

TEST(TimeStep, AnIntegratorsOwnOverridesTheGlobalOne) {
    const SystemDescription system = parse_document(document().dump()).system;
    EXPECT_EQ(time_step_of(integrator(system, "own"), system), kOwnTimeStep);
    EXPECT_EQ(time_step_of(integrator(system, "inherits"), system), kGlobalTimeStep);
}

TEST(TimeStep, TheFirstIsThatOfTheFirstIntegratorScheduledToRunSteps) {
    json doc = document();
    EXPECT_EQ(first_time_step(parse_document(doc.dump()).system), kGlobalTimeStep);
    doc["integrator"]["schedule"]["data"] = json::parse(R"([[1, "own", 10], [2, "inherits", 10]])");
    EXPECT_EQ(first_time_step(parse_document(doc.dump()).system), kOwnTimeStep);
    // An integrator scheduled for no steps never runs.
    doc["integrator"]["schedule"]["data"] = json::parse(R"([[1, "inherits", 0], [2, "own", 10]])");
    EXPECT_EQ(first_time_step(parse_document(doc.dump()).system), kOwnTimeStep);
}

TEST(TimeStep, NoneWhenNeitherTheIntegratorNorTheGlobalGivesOne) {
    json doc = document();
    doc["global"].erase("fundamental");
    const SystemDescription system = parse_document(doc.dump()).system;
    EXPECT_FALSE(time_step_of(integrator(system, "inherits"), system).has_value());
    EXPECT_FALSE(first_time_step(system).has_value());
}

TEST(TimeStep, AnOwnTimeStepMustBePositive) {
    json doc = document();
    doc["integrator"]["own"]["parameters"]["timeStep"] = -0.002;
    const SystemDescription system = parse_document(doc.dump()).system;
    try {
        time_step_of(integrator(system, "own"), system);
        FAIL() << "no error was thrown";
    } catch (const Error& error) {
        EXPECT_EQ(error.status(), STRUCTMD_ERR_INPUT);
        EXPECT_NE(std::string(error.what()).find("integrator.own.parameters.timeStep"), std::string::npos)
            << error.what();
    }
}

}  // namespace
}  // namespace structmd::input
