#include "steps/escape_time.hpp"

#include <memory>

#include "core/error.hpp"
#include "input/tracked_node.hpp"

namespace structmd {

bool EscapeRegion::contains(const double* r) const {
    const auto offset_dot = [r](const double* a, const double* origin) {
        return a[0] * (r[0] - origin[0]) + a[1] * (r[1] - origin[1]) + a[2] * (r[2] - origin[2]);
    };
    if (kind == Kind::halfSpaces) {
        for (size_t k = 0; k < normals.size(); k += 3)
            if (offset_dot(&normals[k], &points[k]) < 0.0) return false;
        return true;
    }
    for (size_t s = 0; s < radii.size(); ++s) {
        const double* c = &centres[3 * s];
        const double d2 = (r[0] - c[0]) * (r[0] - c[0]) + (r[1] - c[1]) * (r[1] - c[1]) + (r[2] - c[2]) * (r[2] - c[2]);
        const double r2 = radii[s] * radii[s];
        if (kind == Kind::allSpheres && d2 > r2) return false;
        if (kind == Kind::anySphere && d2 < r2) return true;
    }
    return kind == Kind::allSpheres;
}

EscapeTime::EscapeTime(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                       EscapeRegion region, std::vector<int64_t> members, bool stop, int64_t toEscape)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), "#step id"),
      region_(std::move(region)),
      members_(std::move(members)),
      escaped_(members_.size(), false),
      stop_(stop),
      toEscape_(toEscape) {}

void EscapeTime::run(Simulation& sim) {
    const int64_t step = sim.current_step();
    std::vector<double> xyz(3 * members_.size());
    sim.get_positions_of(members_.data(), static_cast<int64_t>(members_.size()), xyz.data());
    std::FILE* out = file_.stream();
    const int64_t before = escapes_;
    for (size_t k = 0; k < members_.size(); ++k) {
        if (escaped_[k] || region_.contains(&xyz[3 * k])) continue;
        escaped_[k] = true;
        ++escapes_;
        std::fprintf(out, "%lld %lld\n", static_cast<long long>(step), static_cast<long long>(members_[k]));
    }
    file_.flush();
    if (stop_ && before < toEscape_ && escapes_ >= toEscape_) sim.request_stop(name());
}

namespace {

std::vector<double> read_vectors(const input::Table& table, const std::string& label) {
    std::vector<double> values;
    for (size_t r = 0; r < table.rows(); ++r) {
        const input::TrackedNode cell = table.cell(r, label);
        const std::vector<double> v = cell.as<std::vector<double>>();
        if (v.size() != 3) throw input_error(cell.path(), "expected a vector [x, y, z]");
        values.insert(values.end(), v.begin(), v.end());
    }
    return values;
}

std::unique_ptr<SimulationStep> make(const StepInput& in, EscapeRegion region) {
    std::vector<int64_t> members = in.member_ids();
    const std::string stop = in.parameters.text("stopSimulation");
    if (stop != "true" && stop != "false")
        throw input_error(in.parameters.path("stopSimulation"), "expected \"true\" or \"false\", got \"" + stop + "\"");
    const int64_t toEscape =
        in.parameters.integer("particlesToEscape") > 0 ? in.parameters.integer("particlesToEscape")
                                                       : static_cast<int64_t>(members.size());
    if (toEscape > static_cast<int64_t>(members.size()))
        throw input_error(in.parameters.path("particlesToEscape"),
                          "expected at most the " + std::to_string(members.size()) + " particles watched, got " +
                              std::to_string(toEscape));
    return std::make_unique<EscapeTime>(in.name, in.interval(), in.start(), in.end(),
                                        in.parameters.text("outputFilePath"), std::move(region), std::move(members),
                                        stop == "true", toEscape);
}

std::unique_ptr<SimulationStep> make_spheres(const StepInput& in) {
    const input::Table table = input::read_table(in.node, {"center", "radius"});
    if (table.rows() == 0) throw input_error(in.path + ".data", "expected at least one sphere");
    EscapeRegion region;
    const std::string logicalSum = in.parameters.text("logicalSum");
    if (logicalSum != "all" && logicalSum != "any")
        throw input_error(in.parameters.path("logicalSum"), "expected \"all\" or \"any\", got \"" + logicalSum + "\"");
    region.kind = logicalSum == "all" ? EscapeRegion::Kind::allSpheres : EscapeRegion::Kind::anySphere;
    region.centres = read_vectors(table, "center");
    for (size_t r = 0; r < table.rows(); ++r) {
        const input::TrackedNode cell = table.cell(r, "radius");
        const double radius = cell.as<double>();
        if (!(radius > 0.0)) throw input_error(cell.path(), "expected a positive radius, got " + std::to_string(radius));
        region.radii.push_back(radius);
    }
    return make(in, std::move(region));
}

std::unique_ptr<SimulationStep> make_polygon(const StepInput& in) {
    const input::Table table = input::read_table(in.node, {"normalVector", "independentVector"});
    if (table.rows() == 0) throw input_error(in.path + ".data", "expected at least one plane");
    EscapeRegion region;
    region.kind = EscapeRegion::Kind::halfSpaces;
    region.normals = read_vectors(table, "normalVector");
    region.points = read_vectors(table, "independentVector");
    return make(in, std::move(region));
}

std::vector<StepParameter> escape_parameters(std::initializer_list<StepParameter> own) {
    std::vector<StepParameter> parameters = step_parameters(
        {{"outputFilePath", StepValue::text, nullptr},
         {"stopSimulation", StepValue::text, "false", Must::be_finite, "",
          "\"true\" or \"false\" (text, as UAMMD-structured writes it): end the step call once particlesToEscape "
          "particles have escaped"},
         {"particlesToEscape", StepValue::integer, int64_t{0}, Must::be_non_negative, "particles",
          "escapes that stop the call; 0 (the default): every particle of the group"}});
    parameters.insert(parameters.end(), own.begin(), own.end());
    return parameters;
}

}  // namespace

SimulationStepEntry escape_sphere_time_entry() {
    return {{"GeometricalMeasure", "EscapeSphereTime"},
            escape_parameters({{"logicalSum", StepValue::text, "all", Must::be_finite, "",
                                "\"all\": inside every sphere; \"any\": inside at least one"}}),
            make_spheres,
            {"center", "radius"}};
}

SimulationStepEntry escape_polygon_time_entry() {
    return {{"GeometricalMeasure", "EscapePolygonTime"}, escape_parameters({}), make_polygon,
            {"normalVector", "independentVector"}};
}

}  // namespace structmd
