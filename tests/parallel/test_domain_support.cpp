// The domain check asks the registries what runs under spatial domains, as each component declares
// it (under_domains, underDomains): what declares it loads, what does not is refused by its path.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "core/logger.hpp"
#include "input/description.hpp"
#include "parallel/domain_support.hpp"
#include "simulation/read_simulation.hpp"

namespace structmd {
namespace {

// One batch of two particles with the given pair entry, integrator entry and simulation step.
std::string document(const std::string& pair, const std::string& integrator, const std::string& step) {
    return R"({
      "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "t", "seed": 1}}},
      "global": {
        "types": {"type": ["Types", "Basic"], "labels": ["name", "radius", "mass", "charge"],
                  "data": [["A", 0.5, 1.0, 1.0]]},
        "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[20, 20, 20], 1.0]]}
      },
      "state": {"labels": ["id", "position"], "data": [[0, [0, 0, 0]], [1, [1, 0, 0]]]},
      "topology": {
        "structure": {"labels": ["id", "type"], "data": [[0, "A"], [1, "A"]]},
        "forceField": {
          "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},
          "bonds": {"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"], "data": [[0, 1, 1, 1]]},
          "pairs": )" + pair + R"(
        }
      },
      "integrator": {"move": )" + integrator + R"(,
                     "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                                  "data": [[1, "move", 10]]}},
      "simulationStep": {"out": )" + step + R"(}
    })";
}

const std::string kLennardJones = R"({"type": ["NonBonded", "LennardJonesType1"],
    "parameters": {"condition": "all", "cutOffFactor": 2.5},
    "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1.0, 1.0]]})";
const std::string kVerlet = R"({"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}})";
const std::string kWrite = R"({"type": ["WriteStep", "WriteStep"],
    "parameters": {"intervalStep": 10, "outputFilePath": "t", "outputFormat": "xyz"}})";

// The check's message for `text`, or "" when it supports every entry.
std::string refusal(const std::string& text) {
    const Logger log;
    const input::ParsedDocument parsed = input::parse_document(text);
    const SimulationSpec spec = read_simulation(parsed, log, forcefield_registry());
    try {
        check_domain_support(parsed, spec, forcefield_registry());
    } catch (const Error& error) {
        EXPECT_EQ(error.status(), STRUCTMD_ERR_UNSUPPORTED) << error.what();
        return error.what();
    }
    return "";
}

TEST(DomainSupport, ComponentsThatDeclareItAreSupported) {
    EXPECT_EQ(refusal(document(kLennardJones, kVerlet, kWrite)), "");
    const std::string debyeHuckel = R"({"type": ["NonBonded", "DebyeHuckel"],
        "parameters": {"condition": "all", "cutOffFactor": 3.0, "debyeLength": 1.0, "dielectricConstant": 1.0}})";
    EXPECT_EQ(refusal(document(debyeHuckel, kVerlet, kWrite)), "");
}

TEST(DomainSupport, APairThatDoesNotDeclareItIsRefusedByItsPath) {
    const std::string softCore = R"({"type": ["NonBonded", "Steric6SoftCore"],
        "parameters": {"condition": "all", "cutOffFactor": 2.5, "alpha": 0.5, "n": 2},
        "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1.0, 1.0]]})";
    EXPECT_EQ(refusal(document(softCore, kVerlet, kWrite)),
              "topology.forceField.pairs: forceField entry [\"NonBonded\",\"Steric6SoftCore\"] is not available under "
              "domain decomposition");
}

TEST(DomainSupport, IntegratorsAndStepsAskTheirRegistries) {
    const std::string brownian = R"({"type": ["Brownian", "EulerMaruyama"], "parameters": {"timeStep": 0.001, "viscosity": 1.0}})";
    EXPECT_EQ(refusal(document(kLennardJones, brownian, kWrite)),
              "integrator.move: integrator [\"Brownian\",\"EulerMaruyama\"] is not available under domain decomposition");
    const std::string info = R"({"type": ["UtilsStep", "InfoStep"], "parameters": {"intervalStep": 10}})";
    EXPECT_EQ(refusal(document(kLennardJones, kVerlet, info)),
              "simulationStep.out: simulation step [\"UtilsStep\",\"InfoStep\"] is not available under domain "
              "decomposition");
}

TEST(DomainSupport, AParameterThatCouplesTheWholeSystemIsRefused) {
    const std::string bbk = R"({"type": ["Langevin", "BBK"],
        "parameters": {"timeStep": 0.001, "frictionConstant": 1.0, "stopTransRotSteps": 10}})";
    EXPECT_EQ(refusal(document(kLennardJones, bbk, kWrite)),
              "integrator.move.parameters.stopTransRotSteps: removing the whole system's motion is not available "
              "under domain decomposition");
}

TEST(DomainSupport, ALayoutTheDomainsDoNotCarryIsRefusedByItsPath) {
    std::string text = document(kLennardJones, kVerlet, kWrite);
    const std::string state = R"("labels": ["id", "position"], "data": [[0, [0, 0, 0]], [1, [1, 0, 0]]])";
    text.replace(text.find(state), state.size(),
                 R"("labels": ["id", "position", "direction"],
                    "data": [[0, [0, 0, 0], [1, 0, 0, 0]], [1, [1, 0, 0], [1, 0, 0, 0]]])");
    EXPECT_EQ(refusal(text), "state.labels: column \"direction\" is not available under domain decomposition");
}

// Each domain pairs its own particles and ghosts, not all pairs; slabs need a periodic axis to cut.
TEST(DomainSupport, AllPairsListsAndOpenBoxesAreRefusedByTheirPaths) {
    const std::string overAllPairs = R"({"type": ["NonBonded", "DebyeHuckel"],
        "parameters": {"condition": "all", "cutOffFactor": 3.0, "debyeLength": 1.0, "dielectricConstant": 1.0,
                       "neighbourList": "every"}},
        "every": {"type": ["NBody", "all"]})";
    EXPECT_EQ(refusal(document(overAllPairs, kVerlet, kWrite)),
              "topology.forceField.every: entry [\"NBody\",\"all\"] is not available under domain decomposition");
    std::string open = document(overAllPairs, kVerlet, kWrite);
    const std::string box = "[[20, 20, 20], 1.0]";
    open.replace(open.find(box), box.size(), R"([[20, 20, "inf"], 1.0])");
    EXPECT_EQ(refusal(open), "global.ensemble.data[0][0]: a box with an open axis (a length of 0 or \"inf\") is not "
                             "available under domain decomposition");
}

}  // namespace
}  // namespace structmd
