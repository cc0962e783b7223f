#pragma once
// Integrators and their schedule as read from the integrator section: plain data, each integrator
// naming its component by key and holding its own parameters by name.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "core/state_columns.hpp"
#include "core/registry.hpp"

namespace structmd {

struct IntegratorSpec {
    std::string name;
    std::string path;
    ComponentKey key;
    double timeStep = 0.0;
    double temperature = 0.0;  // k_B T, in energy units
    int group = -1;            // index into ForceFieldSpec::groups; -1: every particle
    bool overdamped = false;   // IntegratorInputs::overdamped
    bool rotates = false;      // IntegratorInputs::rotates: the engine keeps orientations and torques
    ParameterValues parameters;  // the integrator's own (IntegratorInputs::parameters())
};

struct ScheduleStage {
    int integrator = 0;  // index into the integrator list
    int64_t steps = 0;
};

// What the reader knows of an integrator (from its IntegratorInputs).
struct IntegratorComponent {
    ComponentKey key;
    std::vector<Parameter> parameters;
    bool minimiser = false;
    bool needsRadius = false;
    std::function<void(const ParameterValues&, const std::string& path)> validate;
    bool overdamped = false;
    const char* fallbackParameter = nullptr;  // IntegratorInputs::fallbackParameter and fallbackColumn
    StateColumn fallbackColumn = StateColumn::frictionConstant;
    bool rotates = false;
    std::vector<TextOption> textOptions;
    bool magnetic = false;
    const char* radiusParameter = nullptr;  // IntegratorInputs::radiusParameter
    bool oneFluid = false;                  // IntegratorInputs::oneFluid
    bool underDomains = false;              // IntegratorInputs::underDomains
    const char* wholeSystemParameter = nullptr;  // IntegratorInputs::wholeSystemParameter and wholeSystemEffect
    const char* wholeSystemEffect = nullptr;
    std::function<void(const ParameterValues&, const std::array<double, 3>& box, const std::string& path)>
        validateInBox;  // IntegratorInputs::validate_in_box
};

const Registry<IntegratorComponent>& integrator_registry();

}  // namespace structmd
