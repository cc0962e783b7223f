#pragma once
// Everything an engine needs to start, as plain host data: no JSON, so that backend code (compiled
// by nvcc too) never sees the input layer.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/state_columns.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/pair_potential.hpp"
#include "integrators/integrator_spec.hpp"
#include "steps/simulation_step.hpp"

namespace structmd {

// Everything but the simulation steps: plain copyable data, so that a spatial domain's engine
// (parallel/domain_spec.hpp) is made from a selection of the whole system's rows.
struct SystemSpec {
    uint64_t seed = 0;
    // The global id of particle 0 here: non-zero for an engine holding a share of the batches
    // (parallel/batch_split.hpp), whose particles keep their global ids' noise.
    int64_t firstParticleId = 0;
    Constants constants;  // k_B, the electric conversion factor of the units, the largest particle radius
    double velocityKT = 0.0;  // k_B T of drawn velocities: the first scheduled integrator's temperature
    std::array<double, 3> box{0, 0, 0};
    double lambda = 1.0;  // the ensemble's coupling parameter (1 under NVT)
    int64_t currentStep = 0;
    double simulationTime = 0.0;

    std::vector<std::string> typeNames;
    std::vector<std::array<double, 3>> positions;   // by particle id
    std::vector<std::array<double, 3>> velocities;  // empty: draw from Maxwell-Boltzmann
    std::vector<int32_t> typeIndex;
    std::vector<double> mass, radius, charge;
    std::vector<std::array<double, 4>> orientations;  // unit quaternions [q0, q1, q2, q3]; empty: none given
    std::vector<std::array<double, 4>> magnetizations;  // [mx, my, mz, M], body frame; empty: none given
    PerStateColumn<std::vector<double>> columns;        // core/state_columns.hpp; each empty when not given
    std::vector<int32_t> batchId, modelId;

    ForceFieldSpec forceField;
    std::vector<IntegratorSpec> integrators;
    std::vector<ScheduleStage> schedule;
};

struct SimulationSpec : SystemSpec {
    std::vector<std::unique_ptr<SimulationStep>> steps;
    bool stepGraphs = true;  // the engine option "step_graphs": a call's steps as CUDA graphs
};

}  // namespace structmd
