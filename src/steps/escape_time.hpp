#pragma once
// ["GeometricalMeasure","EscapeSphereTime"] and ["GeometricalMeasure","EscapePolygonTime"]: the step
// at which each particle of the group is first seen outside a region, one line `step id` per escape
// (a particle outside at the first firing escapes then). With stopSimulation "true", the step call
// ends (Simulation::request_stop) at the firing where particlesToEscape particles have escaped in
// all; later calls step on, as after UAMMD-structured's stop at that escape. The region is a set
// of spheres (inside all of them, or any, by logicalSum) or a convex polyhedron given as half-spaces
// n . (r - p) >= 0 (the normals point inwards). Positions are the wrapped ones, as UAMMD-structured
// reads them.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

struct EscapeRegion {
    enum class Kind { allSpheres, anySphere, halfSpaces };
    Kind kind = Kind::allSpheres;
    std::vector<double> centres, radii;  // spheres: 3 per centre, 1 per radius
    std::vector<double> normals, points;  // half-spaces: 3 each per plane

    bool contains(const double* r) const;
};

class EscapeTime : public SimulationStep {
public:
    // members: the ids watched, ascending; toEscape: escapes that stop the call (with stop).
    EscapeTime(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
               EscapeRegion region, std::vector<int64_t> members, bool stop, int64_t toEscape);

protected:
    void run(Simulation& sim) override;

private:
    MeasureFile file_;
    EscapeRegion region_;
    std::vector<int64_t> members_;
    std::vector<bool> escaped_;  // by position in members_
    int64_t escapes_ = 0;
    bool stop_;
    int64_t toEscape_;
};

SimulationStepEntry escape_sphere_time_entry();
SimulationStepEntry escape_polygon_time_entry();

}  // namespace structmd
