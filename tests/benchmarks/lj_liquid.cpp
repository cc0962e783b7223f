#include "lj_liquid.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "structmd.hpp"

namespace structmd::benchmarks {

namespace {

void append_number(std::string& text, double value) {
    char digits[32];
    const auto end = std::to_chars(digits, digits + sizeof digits, value).ptr;  // shortest exact form
    text.append(digits, end);
}

void append_integer(std::string& text, int64_t value) {
    char digits[24];
    const auto end = std::to_chars(digits, digits + sizeof digits, value).ptr;
    text.append(digits, end);
}

// Nine significant digits: a float survives the round trip exactly, so the single-precision engine
// starts from the same lattice as from the full text, and the text (parsed by the engine at about
// 20 MB/s) is a third shorter; a double loses below 1e-8 sigma, which the melting forgets at once.
void append_position(std::string& text, double x, double y, double z) {
    char digits[96];
    char* end = digits;
    *end++ = '[';
    for (const double value : {x, y, z}) {
        if (end != digits + 1) *end++ = ',';
        end = std::to_chars(end, digits + sizeof digits, value, std::chars_format::general, 9).ptr;
    }
    *end++ = ']';
    text.append(digits, end);
}

// The system and global sections of a one-type system (A: mass 1, radius 0.5) in an orthorhombic box.
void append_system_and_global(std::string& json, const char* name, const double lengths[3], double temperature) {
    json += R"({"system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": ")";
    json += name;
    json += R"(", "seed": 1}}},)";
    json += R"("global": {"units": {"type": ["Units", "None"]},)"
            R"("types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],)"
            R"( "data": [["A", 1.0, 0.5, 0.0]]},)"
            R"("ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[)";
    for (int axis = 0; axis < 3; ++axis) {
        append_number(json, lengths[axis]);
        json += axis < 2 ? "," : "],";
    }
    append_number(json, temperature);
    json += "]]}},";
}

// An integrator section of one entry, run by a one-stage schedule. entry: the entry's JSON object.
void append_integrator(std::string& json, const char* name, const std::string& entry, int64_t steps) {
    json += R"("integrator": {")";
    json += name;
    json += R"(": )" + entry;
    json += R"(, "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],)"
            R"( "data": [[1, ")";
    json += name;
    json += R"(", )";
    append_integer(json, steps);
    json += "]]}},";
}

// {"type": [...], "parameters": {..., "timeStep": dt}}, the parameters before the time step given.
std::string integrator_entry(const char* type, const std::string& parameters, double timeStep) {
    std::string entry = std::string(R"({"type": )") + type + R"(, "parameters": {)" + parameters + R"("timeStep": )";
    append_number(entry, timeStep);
    return entry + "}}";
}

}  // namespace

int64_t cells_per_edge(int64_t requested_particles) {
    const auto k = static_cast<int64_t>(std::llround(std::cbrt(static_cast<double>(requested_particles) / 4.0)));
    return std::max<int64_t>(k, 1);
}

std::string lj_liquid_input(const LjLiquid& liquid) {
    const double lattice = std::cbrt(4.0 / kDensity);
    const double box = lattice * static_cast<double>(liquid.cells);
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    const int64_t perBatch = 4 * liquid.cells * liquid.cells * liquid.cells;
    const int64_t particles = perBatch * liquid.batches;

    std::string json;
    // About 45 bytes per state row and 12 per structure row.
    json.reserve(static_cast<size_t>(particles) * 64 + 2048);
    const double lengths[3] = {box, box, box};
    append_system_and_global(json, "lj_liquid", lengths, kTemperature);
    append_integrator(json, "vv", integrator_entry(R"(["Verlet", "VelocityVerlet"])", "", liquid.timeStep),
                      liquid.scheduleSteps);

    // Lattice sites shifted by a quarter cell so none sits on the box boundary at -L/2.
    json += R"("state": {"labels": ["id", "position"], "data": [)";
    int64_t id = 0;
    for (int64_t batch = 0; batch < liquid.batches; ++batch)
    for (int64_t i = 0; i < liquid.cells; ++i)
        for (int64_t j = 0; j < liquid.cells; ++j)
            for (int64_t l = 0; l < liquid.cells; ++l)
                for (const auto& site : basis) {
                    json += id > 0 ? ",[" : "[";
                    append_integer(json, id);
                    json += ',';
                    append_position(json, -0.5 * box + lattice * (static_cast<double>(i) + site[0] + 0.25),
                                    -0.5 * box + lattice * (static_cast<double>(j) + site[1] + 0.25),
                                    -0.5 * box + lattice * (static_cast<double>(l) + site[2] + 0.25));
                    json += ']';
                    ++id;
                }
    json += "]},";

    const bool batched = liquid.batches > 1;
    json += batched ? R"("topology": {"structure": {"labels": ["id", "type", "batchId"], "data": [)"
                    : R"("topology": {"structure": {"labels": ["id", "type"], "data": [)";
    for (int64_t p = 0; p < particles; ++p) {
        json += p > 0 ? ",[" : "[";
        append_integer(json, p);
        json += R"(,"A")";
        if (batched) {
            json += ',';
            append_integer(json, p / perBatch);
        }
        json += ']';
    }
    json += "]},";
    json += R"("forceField": {"nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": )";
    append_number(json, (kCutOff + liquid.skin) / kCutOff);
    json += "}},";
    if (liquid.asExpression) {
        json += R"("lj": {"type": ["NonBonded", "Expression"], "parameters": {"energy": )"
                R"json("4*epsilon*((sigma/r)^12 - (sigma/r)^6)", "cutOff": )json";
    } else {
        json += R"("lj": {"type": ["NonBonded", "LennardJonesType1"], "parameters": {"cutOffFactor": )";
    }
    append_number(json, kCutOff);
    json += R"(, "condition": "all", "shift": )";
    json += liquid.shiftEnergy ? "true" : "false";
    json += R"(}, "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1.0, 1.0]]}}}})";
    return json;
}

std::string bead_chains_input(const BeadChains& melt) {
    const auto rows = static_cast<int64_t>(std::llround(std::sqrt(static_cast<double>(melt.chains))));
    const double spacing = std::cbrt(1.0 / 0.85);
    const double lengths[3] = {spacing * static_cast<double>(melt.beads), spacing * static_cast<double>(rows),
                               spacing * static_cast<double>(rows)};
    const int64_t particles = melt.beads * rows * rows;

    std::string json;
    json.reserve(static_cast<size_t>(particles) * 110 + 2048);
    append_system_and_global(json, "bead_chains", lengths, 1.0);
    append_integrator(json, "bbk", integrator_entry(R"(["Langevin", "BBK"])", R"("frictionConstant": 1.0, )", melt.timeStep),
                      melt.scheduleSteps);

    // Chain c is lattice row (c / rows, c % rows); its beads run along x.
    const auto id_of = [&](int64_t chain, int64_t bead) { return chain * melt.beads + bead; };
    json += R"("state": {"labels": ["id", "position"], "data": [)";
    for (int64_t chain = 0; chain < rows * rows; ++chain)
        for (int64_t bead = 0; bead < melt.beads; ++bead) {
            json += chain + bead > 0 ? ",[" : "[";
            append_integer(json, id_of(chain, bead));
            json += ',';
            append_position(json, -0.5 * lengths[0] + spacing * (static_cast<double>(bead) + 0.25),
                            -0.5 * lengths[1] + spacing * (static_cast<double>(chain / rows) + 0.25),
                            -0.5 * lengths[2] + spacing * (static_cast<double>(chain % rows) + 0.25));
            json += ']';
        }
    json += "]},";

    json += R"("topology": {"structure": {"labels": ["id", "type", "modelId"], "data": [)";
    for (int64_t p = 0; p < particles; ++p) {
        json += p > 0 ? ",[" : "[";
        append_integer(json, p);
        json += R"(,"A",)";
        append_integer(json, p / melt.beads);
        json += ']';
    }
    json += "]},";
    const double wcaCutOff = std::pow(2.0, 1.0 / 6.0);
    json += R"("forceField": {"nl": {"type": ["VerletConditionalListSet", "nonExcluded"], "parameters": {"cutOffVerletFactor": )";
    append_number(json, (wcaCutOff + melt.skin) / wcaCutOff);
    json += R"(}, "labels": ["id", "id_list"], "data": [)";
    for (int64_t p = 0; p < particles; ++p) {
        const int64_t bead = p % melt.beads;
        json += p > 0 ? ",[" : "[";
        append_integer(json, p);
        json += ",[";
        if (bead > 0) append_integer(json, p - 1);
        if (bead > 0 && bead + 1 < melt.beads) json += ',';
        if (bead + 1 < melt.beads) append_integer(json, p + 1);
        json += "]]";
    }
    json += "]},";
    json += R"("wca": {"type": ["NonBonded", "WCAType1"], "parameters": {"cutOffFactor": )";
    append_number(json, wcaCutOff);
    json += R"(, "condition": "nonExcluded"}, "labels": ["name_i", "name_j", "epsilon", "sigma"],)"
            R"( "data": [["A", "A", 1.0, 1.0]]},)";
    json += R"("bonds": {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 100.0, "r0": 1.0},)"
            R"( "labels": ["id_i", "id_j"], "data": [)";
    bool first = true;
    for (int64_t chain = 0; chain < rows * rows; ++chain)
        for (int64_t bead = 0; bead + 1 < melt.beads; ++bead) {
            json += first ? "[" : ",[";
            first = false;
            append_integer(json, id_of(chain, bead));
            json += ',';
            append_integer(json, id_of(chain, bead + 1));
            json += ']';
        }
    json += "]},";
    json += R"("bending": {"type": ["Bond3", "KratkyPorodCommon_K"], "parameters": {"K": 2.0},)"
            R"( "labels": ["id_i", "id_j", "id_k"], "data": [)";
    first = true;
    for (int64_t chain = 0; chain < rows * rows; ++chain)
        for (int64_t bead = 0; bead + 2 < melt.beads; ++bead) {
            json += first ? "[" : ",[";
            first = false;
            for (int64_t k = 0; k < 3; ++k) {
                if (k > 0) json += ',';
                append_integer(json, id_of(chain, bead + k));
            }
            json += ']';
        }
    json += "]}}}}";
    return json;
}

std::string create_options(const std::string& backend, const std::string& precision, int threads,
                           const std::string& pairTraversal) {
    nlohmann::json options = {{"backend", backend}, {"precision", precision}, {"log", "warning"}};
    if (threads > 0) options["threads"] = threads;
    if (pairTraversal != "auto") options["pair_traversal"] = pairTraversal;
    return options.dump();
}

nlohmann::json engine_info(const structmd_sim* sim) { return nlohmann::json::parse(host::info(sim)); }

nlohmann::json engine_counters(structmd_sim* sim) {
    char text[1024];  // the header promises 512 bytes suffice; keys may be added
    host::check(structmd_get_counters(sim, text, sizeof text), sim, "structmd_get_counters");
    return nlohmann::json::parse(text);
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t half = values.size() / 2;
    return values.size() % 2 == 1 ? values[half] : 0.5 * (values[half - 1] + values[half]);
}

bool open_csv(std::ofstream& csv, const std::string& path, const std::string& header) {
    csv.open(path);
    if (!csv) {
        std::fprintf(stderr, "cannot write %s\n", path.c_str());
        return false;
    }
    csv << header << "\n";
    return true;
}

}  // namespace structmd::benchmarks
