// A host in a decimal-comma locale (setlocale(LC_ALL, "de_DE.UTF-8")) loads, steps and writes the
// same numbers as one in the "C" locale: an Expression's literals, a LAMMPS table file and a
// trajectory file; and a force callback still runs in the host's own locale (issue 37, defect 5).
// ctest makes the locale with localedef into the build tree (LOCPATH).
#include <clocale>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "robustness_support.hpp"

namespace {

using nlohmann::json;
using structmd::host::Handle;
using structmd::robustness::kHandleOptions;
using structmd::robustness::read_text;

const char* const kCommaLocale = "de_DE.UTF-8";

std::string formatted(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", value);
    return text;
}

std::string temporary(const std::string& name) { return ::testing::TempDir() + "structmd_locale_" + name; }

// Three particles in a harmonic trap written as an Expression with decimal literals, and a pair
// term read from a LAMMPS table file; a trajectory in xyz after every step.
json document(const std::string& table, const std::string& trajectory) {
    return {
        {"system", {{"info", {{"type", {"Simulation", "Information"}}, {"parameters", {{"name", "locale"}, {"seed", 1}}}}}}},
        {"global",
         {{"types", {{"type", {"Types", "Basic"}}, {"labels", {"name", "mass", "radius", "charge"}}, {"data", {{"A", 1.0, 0.5, 0.0}}}}},
          {"ensemble", {{"type", {"Ensemble", "NVT"}}, {"labels", {"box", "temperature"}}, {"data", {{{10.0, 10.0, 10.0}, 1.0}}}}}}},
        {"integrator",
         {{"vv", {{"type", {"Verlet", "VelocityVerlet"}}, {"parameters", {{"timeStep", 0.001}}}}},
          {"schedule", {{"type", {"Schedule", "Integrator"}}, {"labels", {"order", "integrator", "steps"}}, {"data", {{1, "vv", 3}}}}}}},
        {"state", {{"labels", {"id", "position", "velocity"}},
                   {"data", {{0, {0.25, 0.0, 0.0}, {0.5, 0.0, 0.0}}, {1, {1.5, 0.125, 0.0}, {0.0, 0.25, 0.0}}, {2, {0.0, 1.375, 0.5}, {0.0, 0.0, 0.75}}}}}},
        {"topology",
         {{"structure", {{"labels", {"id", "type"}}, {"data", {{0, "A"}, {1, "A"}, {2, "A"}}}}},
          {"forceField",
           {{"trap", {{"type", {"External", "Expression"}}, {"parameters", {{"energy", "0.5 * k * (x^2 + y^2 + z^2) + 0.25"}, {"k", 2.5}}}}},
            {"nl", {{"type", {"VerletConditionalListSet", "all"}}, {"parameters", {{"cutOffVerletFactor", 1.1}}}}},
            {"pair", {{"type", {"NonBonded", "Tabulated"}}, {"parameters", {{"condition", "all"}, {"N", 100}}},
                      {"labels", {"name_i", "name_j", "file", "keyword"}}, {"data", {{"A", "A", table, "T"}}}}}}}}},
        {"simulationStep",
         {{"xyz", {{"type", {"WriteStep", "WriteStep"}},
                   {"parameters", {{"intervalStep", 1}, {"outputFilePath", trajectory}, {"outputFormat", "xyz"}}}}}}}};
}

// A soft repulsion tabulated from r = 0.5 to 2.5: U = 0.5 (2.5 - r)^2.
std::string write_table() {
    const std::string path = temporary("soft.table");
    std::ofstream out(path);
    out << "T\nN 5\n\n";
    for (int i = 0; i < 5; ++i) {
        const double r = 0.5 + 0.5 * i;
        out << i + 1 << ' ' << r << ' ' << 0.5 * (2.5 - r) * (2.5 - r) << ' ' << (2.5 - r) << '\n';
    }
    return path;
}

struct Outcome {
    double energy = 0.0;
    std::string trajectory;
    std::string formattedInCallback;
};

Outcome run(const std::string& name) {
    const std::string trajectory = temporary(name);
    Handle sim(kHandleOptions);
    Outcome result;
    EXPECT_EQ(structmd_load_string(sim.get(), document(write_table(), trajectory).dump().c_str()), STRUCTMD_OK)
        << structmd_last_error(sim.get());
    const auto callback = [](const double*, double*, int64_t, double*, double*, int64_t, void* user) -> int32_t {
        static_cast<Outcome*>(user)->formattedInCallback = formatted(1.5);
        return 0;
    };
    EXPECT_EQ(structmd_set_force_callback(sim.get(), callback, &result), STRUCTMD_OK);
    EXPECT_EQ(structmd_run(sim.get()), STRUCTMD_OK) << structmd_last_error(sim.get());
    EXPECT_EQ(structmd_get_energy(sim.get(), "potential", &result.energy), STRUCTMD_OK);
    result.trajectory = read_text(trajectory + ".xyz");
    return result;
}

TEST(Locale, ACommaLocaleChangesNoNumberReadOrWritten) {
    ASSERT_NE(std::setlocale(LC_ALL, "C"), nullptr);
    const Outcome classic = run("classic");
    ASSERT_NE(std::setlocale(LC_ALL, kCommaLocale), nullptr) << kCommaLocale << " is not installed (LOCPATH)";
    ASSERT_EQ(formatted(1.5), "1,5") << "the locale does not write decimal commas";
    const Outcome comma = run("comma");
    std::setlocale(LC_ALL, "C");
    EXPECT_EQ(comma.energy, classic.energy);
    EXPECT_NE(classic.trajectory.find('.'), std::string::npos) << classic.trajectory;
    EXPECT_EQ(classic.trajectory.find(','), std::string::npos) << classic.trajectory;
    EXPECT_EQ(comma.trajectory, classic.trajectory);
    EXPECT_EQ(classic.formattedInCallback, "1.5");
    EXPECT_EQ(comma.formattedInCallback, "1,5");
}

}  // namespace
