// The tabulated reference scenes (tests/reference/data/table_*.json) on another backend or precision
// against the CPU in double: forces and energy at the start, then positions after 50 velocity-Verlet
// steps. `--backend=cuda` (ctest tabulated.backends_cuda, label gpu) exits 77 when no GPU is usable;
// `--backend=cpu --precision=mixed` checks the single-precision pair path on the CPU.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tabulated_support.hpp"

namespace structmd_tabulated {
namespace {

std::string g_backend = "cpu";
std::string g_precision = "double";

std::string data_path(const std::string& file) { return std::string(STRUCTMD_REFERENCE_DATA_DIR) + "/" + file; }

Json reference_input(const std::string& name) {
    std::ifstream in(data_path(name + ".json"));
    Json doc = Json::parse(in);
    for (auto& [entryName, entry] : doc["topology"]["forceField"].items()) {
        if (entry.contains("parameters") && entry["parameters"].contains("file"))
            entry["parameters"]["file"] = data_path(entry["parameters"]["file"]);
        if (entry.contains("labels"))
            for (size_t c = 0; c < entry["labels"].size(); ++c)
                if (entry["labels"][c] == "file")
                    for (auto& row : entry["data"]) row[c] = data_path(row[c]);
    }
    return doc;
}

SimHandle load_on(const Json& doc, const std::string& backend, const std::string& precision) {
    structmd_sim* raw = nullptr;
    EXPECT_EQ(structmd_create(structmd_physics::create_options(backend, precision).c_str(), &raw), STRUCTMD_OK);
    SimHandle sim(raw);
    EXPECT_EQ(structmd_load_string(raw, doc.dump().c_str()), STRUCTMD_OK) << structmd_last_error(raw);
    return sim;
}

class Backends : public ::testing::TestWithParam<std::string> {};

TEST_P(Backends, AgreeWithTheCpuInDouble) {
    const Json doc = reference_input(GetParam());
    SimHandle reference = load_on(doc, "cpu", "double");
    SimHandle other = load_on(doc, g_backend, g_precision);
    int64_t n = 0;
    ASSERT_EQ(structmd_get_num_particles(reference.get(), &n), STRUCTMD_OK);
    const double tolerance = g_precision == "double" ? 1e-10 : 1e-4;
    const double forceDeviation =
        structmd_physics::max_relative_deviation(forces(other.get(), n), forces(reference.get(), n));
    const double energyDeviation = structmd_physics::relative_deviation(potential(other.get()), potential(reference.get()));
    ASSERT_EQ(structmd_step(reference.get(), 50), STRUCTMD_OK) << structmd_last_error(reference.get());
    ASSERT_EQ(structmd_step(other.get(), 50), STRUCTMD_OK) << structmd_last_error(other.get());
    std::vector<double> a(3 * n), b(3 * n);
    structmd_get_positions(reference.get(), a.data(), n);
    structmd_get_positions(other.get(), b.data(), n);
    double moved = 0;
    for (size_t k = 0; k < a.size(); ++k) moved = std::max(moved, std::abs(a[k] - b[k]));
    std::printf("[ deviation ] %s %s/%s against cpu/double: forces %.2e, energy %.2e, positions after 50 steps %.2e\n",
                GetParam().c_str(), g_backend.c_str(), g_precision.c_str(), forceDeviation, energyDeviation, moved);
    EXPECT_LT(forceDeviation, tolerance);
    EXPECT_LT(energyDeviation, tolerance);
    EXPECT_LT(moved, g_precision == "double" ? 1e-8 : 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Tables, Backends, ::testing::Values("table_pair", "table_bonds", "table_dihedrals"));

}  // namespace
}  // namespace structmd_tabulated

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        if (arg.rfind("--backend=", 0) == 0) structmd_tabulated::g_backend = arg.substr(10);
        if (arg.rfind("--precision=", 0) == 0) structmd_tabulated::g_precision = arg.substr(12);
    }
    structmd_sim* probe = nullptr;
    if (structmd_create(structmd_physics::create_options(structmd_tabulated::g_backend, "double").c_str(), &probe) !=
        STRUCTMD_OK) {
        std::printf("skipped: no usable %s backend: %s\n", structmd_tabulated::g_backend.c_str(), structmd_last_error(nullptr));
        return 77;
    }
    structmd_destroy(probe);
    return RUN_ALL_TESTS();
}
