// Bad inputs through structmd_load_string and structmd_load_file: each must fail with the expected
// status and a message that starts with where the culprit is, never crash, and leave the handle that
// failed able to load a good input and step it. The cases live in bad_inputs/cases.json; a second
// test puts a value of the wrong type in place of every value of bad_inputs/base.json.
#include <pthread.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "robustness_support.hpp"

namespace {

using nlohmann::json;
using namespace structmd::robustness;
using structmd::host::check;
using structmd::host::Handle;

struct BadInput {
    std::string name;
    std::string text;
    structmd_status status;
    std::string where;  // the message starts with where + ": "
    std::string what;   // and contains this after it
};

structmd_status status_named(const std::string& name) {
    static const std::map<std::string, structmd_status> statuses = {
        {"STRUCTMD_ERR_ARGUMENT", STRUCTMD_ERR_ARGUMENT}, {"STRUCTMD_ERR_INPUT", STRUCTMD_ERR_INPUT},
        {"STRUCTMD_ERR_STATE", STRUCTMD_ERR_STATE},       {"STRUCTMD_ERR_NUMERICAL", STRUCTMD_ERR_NUMERICAL},
        {"STRUCTMD_ERR_IO", STRUCTMD_ERR_IO},             {"STRUCTMD_ERR_MEMORY", STRUCTMD_ERR_MEMORY}};
    return statuses.at(name);
}

std::string nested_arrays(size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

// The document a case describes (see "about" in cases.json).
std::string case_text(const json& entry, const std::string& base) {
    if (entry.contains("text")) return entry.at("text").get<std::string>();
    if (entry.contains("edit")) {
        const auto find = entry.at("edit").at("find").get<std::string>();
        const size_t at = base.find(find);
        if (at == std::string::npos || base.find(find, at + 1) != std::string::npos)
            throw std::runtime_error("edit.find must occur exactly once in base.json: " + find);
        return std::string(base).replace(at, find.size(), entry.at("edit").at("replace").get<std::string>());
    }
    if (entry.contains("patch")) return json::parse(base).patch(entry.at("patch")).dump(1);
    if (entry.contains("truncate")) {
        const auto bytes = entry.at("truncate").get<long>();
        return base.substr(0, static_cast<size_t>(bytes >= 0 ? bytes : static_cast<long>(base.size()) + bytes));
    }
    if (entry.contains("nested_arrays")) {
        const json& nested = entry.at("nested_arrays");
        const std::string arrays = nested_arrays(nested.at("depth").get<size_t>());
        const auto at = nested.at("at").get<std::string>();
        if (at.empty()) return arrays;
        // Built as text: nlohmann::json itself would recurse that deep when dumping.
        const std::string marker = "\"@nested@\"";
        std::string text = json::parse(base).patch(json::array({{{"op", "replace"}, {"path", at}, {"value", "@nested@"}}})).dump();
        return text.replace(text.find(marker), marker.size(), arrays);
    }
    throw std::runtime_error("case " + entry.at("name").get<std::string>() + " gives no document");
}

std::vector<BadInput> cases_from_file() {
    const std::string base = base_input_text();
    const json file = json::parse(read_text(std::string(STRUCTMD_ROBUSTNESS_DIR) + "/bad_inputs/cases.json"));
    std::vector<BadInput> cases;
    for (const json& entry : file.at("cases"))
        cases.push_back({entry.at("name").get<std::string>(), case_text(entry, base),
                         status_named(entry.at("status").get<std::string>()), entry.at("where").get<std::string>(),
                         entry.at("what").get<std::string>()});
    return cases;
}

using Loader = std::function<structmd_status(structmd_sim*, const std::string&)>;

structmd_status load_string(structmd_sim* sim, const std::string& text) { return structmd_load_string(sim, text.c_str()); }

structmd_status load_file(structmd_sim* sim, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() /
                      ("structmd_bad_input_" + std::to_string(::getpid()) + ".json");
    std::ofstream(path, std::ios::binary) << text;
    const structmd_status status = structmd_load_file(sim, path.c_str());
    std::filesystem::remove(path);
    return status;
}

int64_t step_of(structmd_sim* sim) {
    int64_t step = -1;
    EXPECT_EQ(structmd_get_step(sim, &step), STRUCTMD_OK) << structmd_last_error(sim);
    return step;
}

// The handle that just failed still holds the simulation it held before, at heldStep (none when
// nullopt), which steps on; it then loads the good input and steps it.
void expect_usable_after_failure(structmd_sim* sim, const std::string& good, std::optional<int64_t> heldStep) {
    if (heldStep) {
        EXPECT_EQ(step_of(sim), *heldStep) << "the simulation loaded before the failed load was not kept";
        EXPECT_EQ(structmd_step(sim, 1), STRUCTMD_OK) << structmd_last_error(sim);
        EXPECT_EQ(step_of(sim), *heldStep + 1);
    } else {
        EXPECT_EQ(structmd_step(sim, 1), STRUCTMD_ERR_STATE) << structmd_last_error(sim);
    }
    ASSERT_EQ(structmd_load_string(sim, good.c_str()), STRUCTMD_OK) << structmd_last_error(sim);
    ASSERT_EQ(structmd_step(sim, 10), STRUCTMD_OK) << structmd_last_error(sim);
    EXPECT_EQ(step_of(sim), 10);
    for (double x : positions(sim)) EXPECT_TRUE(std::isfinite(x));
}

void expect_rejected(const BadInput& bad, const Loader& load, const std::string& good) {
    Handle sim(kHandleOptions);
    // A simulation is loaded and stepped first: the failed load must leave it as it was.
    check(structmd_load_string(sim.get(), good.c_str()), sim.get(), "structmd_load_string");
    check(structmd_step(sim.get(), 3), sim.get(), "structmd_step");
    const std::vector<double> heldPositions = positions(sim.get());
    const structmd_status status = load(sim.get(), bad.text);
    const std::string message = structmd_last_error(sim.get());
    EXPECT_EQ(status, bad.status) << message;
    EXPECT_EQ(message.rfind(bad.where + ": ", 0), 0u) << "message: " << message << "\nexpected it to start with: "
                                                      << bad.where << ": ";
    EXPECT_NE(message.find(bad.what, bad.where.size()), std::string::npos)
        << "message: " << message << "\nexpected it to contain: " << bad.what;
    EXPECT_EQ(positions(sim.get()), heldPositions);
    expect_usable_after_failure(sim.get(), good, 3);
}

TEST(BadInputs, EveryCaseOfTheCorpusFailsNamingWhere) {
    const std::string good = base_input_text();
    const std::vector<BadInput> cases = cases_from_file();
    ASSERT_FALSE(cases.empty());
    for (const BadInput& bad : cases) {
        SCOPED_TRACE(bad.name);
        {
            SCOPED_TRACE("structmd_load_string");
            expect_rejected(bad, load_string, good);
        }
        {
            SCOPED_TRACE("structmd_load_file");
            expect_rejected(bad, load_file, good);
        }
    }
}

// An unknown component is answered with the few registered names nearest to it, on one line, not
// with the registry's hundred-odd entries.
TEST(BadInputs, AnUnknownComponentIsAnsweredOnOneShortLine) {
    json document = json::parse(base_input_text());
    document["topology"]["forceField"]["bonds"]["type"] = {"Bond2", "Harmonic_K_r0"};
    Handle sim(kHandleOptions);
    EXPECT_EQ(structmd_load_string(sim.get(), document.dump().c_str()), STRUCTMD_ERR_INPUT);
    const std::string message = structmd_last_error(sim.get());
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_LT(message.size(), 300u) << message;
    EXPECT_NE(message.find("[\"Bond2\", \"HarmonicCommon_K_r0\"]"), std::string::npos) << message;
}

// Values of every JSON type but the one the value has (and a fraction in place of an integer).
std::vector<json> wrong_types(const json& value) {
    const json object = {{"a", 1}};
    if (value.is_number_integer()) return {"7", nullptr, json::array({1}), object, true, 0.5};
    if (value.is_number()) return {"1.0", nullptr, json::array({1.0}), object, true};
    if (value.is_string()) return {7, nullptr, json::array({value}), object, true};
    if (value.is_array()) return {7, "x", object, nullptr};
    return {7, "x", json::array({1}), nullptr};
}

struct Site {
    json::json_pointer pointer;
    std::string path;  // where the engine reports a wrong value put there
};

// Every value under node, with the path the engine names for it: its own (path), except the two
// strings of a component's "type", which the engine reads and reports as one value (reported).
void collect_sites(const json& node, const json::json_pointer& pointer, const std::string& path,
                   const std::string& reported, std::vector<Site>& sites) {
    sites.push_back({pointer, reported});
    if (node.is_object())
        for (const auto& [key, child] : node.items())
            collect_sites(child, pointer / key, path + "." + key, path + "." + key, sites);
    else if (node.is_array())
        for (size_t i = 0; i < node.size(); ++i) {
            const std::string element = path + "[" + std::to_string(i) + "]";
            const bool typePair = pointer.back() == "type";
            collect_sites(node[i], pointer / i, element, typePair ? path : element, sites);
        }
}

TEST(BadInputs, AWrongTypeAnywhereFailsNamingItsPath) {
    const std::string good = base_input_text();
    const json base = json::parse(good);
    std::vector<Site> sites;
    for (const auto& [section, node] : base.items()) collect_sites(node, json::json_pointer("/" + section), section, section, sites);
    ASSERT_GT(sites.size(), 100u);  // every section, down to each coordinate
    for (const Site& site : sites) {
        for (const json& value : wrong_types(base.at(site.pointer))) {
            json document = base;
            document.at(site.pointer) = value;
            const BadInput bad{site.pointer.to_string(), document.dump(), STRUCTMD_ERR_INPUT, site.path, "expected"};
            SCOPED_TRACE(site.pointer.to_string() + " = " + value.dump());
            expect_rejected(bad, load_string, good);
            expect_rejected(bad, load_file, good);
        }
    }
}

// A directory cannot be read and a device may never end (/dev/zero would be read until memory ran
// out): the input and a checkpoint are refused as IO, naming the file, before a byte is read (issue
// 37, defects 3 and 9).
TEST(BadInputs, ADirectoryOrADeviceIsRefusedUnread) {
    const std::string good = base_input_text();
    const std::string directory = ::testing::TempDir();
    Handle sim(kHandleOptions);
    std::optional<int64_t> heldStep;  // none at first, then the 10 steps of the good input
    for (const auto& [path, why] : {std::pair<std::string, std::string>{directory, "a directory, not a file"},
                                    {"/dev/zero", "not a regular file"}}) {
        EXPECT_EQ(structmd_load_file(sim.get(), path.c_str()), STRUCTMD_ERR_IO) << path;
        const std::string message = structmd_last_error(sim.get());
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find(why), std::string::npos) << message;
        expect_usable_after_failure(sim.get(), good, heldStep);
        heldStep = 10;
        EXPECT_EQ(structmd_load_checkpoint(sim.get(), path.c_str()), STRUCTMD_ERR_IO) << path;
        EXPECT_NE(std::string(structmd_last_error(sim.get())).find(why), std::string::npos)
            << structmd_last_error(sim.get());
    }
}

// Runs body on a thread with a 256 KiB stack, as a host's worker thread may have: whatever the
// input decides must not recurse deeper than that allows.
void on_a_small_stack(const std::function<void()>& body) {
    pthread_attr_t attributes;
    pthread_attr_init(&attributes);
    pthread_attr_setstacksize(&attributes, 256 * 1024);
    pthread_t thread;
    const auto run = [](void* argument) -> void* {
        (*static_cast<const std::function<void()>*>(argument))();
        return nullptr;
    };
    ASSERT_EQ(pthread_create(&thread, &attributes, run, const_cast<std::function<void()>*>(&body)), 0);
    pthread_join(thread, nullptr);
    pthread_attr_destroy(&attributes);
}

// Handle options out of an int's range are refused, not wrapped (4294967297 threads ran with 1),
// and a value nested deep is named by its kind, not written out level by level: on a thread with a
// 256 KiB stack too (issue 37, defects 2 and 9).
std::string create_status(const std::string& options, structmd_status& status) {
    structmd_sim* sim = nullptr;
    status = structmd_create(options.c_str(), &sim);
    structmd_destroy(sim);
    return structmd_last_error(nullptr);
}

TEST(BadInputs, OptionsOutOfRangeOrNestedDeepAreArgumentErrors) {
    structmd_status status = STRUCTMD_OK;
    for (const char* threads : {"4294967297", "3000000000", "18446744073709551615", "-1", "0", "2.5"}) {
        const std::string message = create_status(std::string(R"({"backend": "cpu", "threads": )") + threads + "}", status);
        EXPECT_EQ(status, STRUCTMD_ERR_ARGUMENT) << threads;
        EXPECT_NE(message.find("option \"threads\": expected an integer from 1 to 2147483647"), std::string::npos)
            << message;
    }
    // A number no double holds is malformed options, not an internal error (fuzz_create_options).
    EXPECT_NE(create_status(R"({"backend": "cpu", "threads": 2222e7662})", status).find("not valid JSON"),
              std::string::npos);
    EXPECT_EQ(status, STRUCTMD_ERR_ARGUMENT);
    const std::string nested = R"({"backend": "cpu", "threads": )" + nested_arrays(100000) + "}";
    std::string message;
    on_a_small_stack([&] { message = create_status(nested, status); });
    EXPECT_EQ(status, STRUCTMD_ERR_ARGUMENT);
    EXPECT_NE(message.find("got an array"), std::string::npos) << message.substr(0, 200);
}

// Loads `document` and steps it twice on a thread with a 256 KiB stack; the status of the first call
// that failed (or OK) and its message.
std::pair<structmd_status, std::string> load_and_step_on_a_small_stack(const std::string& document) {
    structmd_status status = STRUCTMD_OK;
    std::string message;
    on_a_small_stack([&] {
        Handle sim(kHandleOptions);
        status = structmd_load_string(sim.get(), document.c_str());
        if (status == STRUCTMD_OK) status = structmd_step(sim.get(), 2);
        message = structmd_last_error(sim.get());
    });
    return {status, message};
}

std::string with_field_energy(const std::string& energy) {
    json document = json::parse(base_input_text());
    document["topology"]["forceField"]["field"] = {{"type", {"External", "Expression"}},
                                                   {"parameters", {{"energy", energy}}}};
    return document.dump();
}

// An Expression nested 30,000 parentheses deep, and a flat sum of 100,000 terms (a chain as deep),
// are INPUT errors at the entry's energy on a thread with a 256 KiB stack: the parser and the walks
// over the expression recurse no deeper than a bound, which still leaves room for 90 nested
// parentheses and a sum of 450 terms, with their derivatives (issue 37, defect 2).
TEST(BadInputs, AnExpressionNestedTooDeepIsAnInputError) {
    std::string sum = "x";
    for (int k = 0; k < 100000; ++k) sum += " + x";
    for (const std::string& energy : {std::string(30000, '(') + "x" + std::string(30000, ')'), sum}) {
        const auto [status, message] = load_and_step_on_a_small_stack(with_field_energy(energy));
        EXPECT_EQ(status, STRUCTMD_ERR_INPUT) << energy.substr(0, 20);
        EXPECT_EQ(message.rfind("topology.forceField.field.parameters.energy", 0), 0u) << message.substr(0, 300);
        EXPECT_NE(message.find("deep"), std::string::npos) << message.substr(0, 300);
    }
    std::string moderate = "0.001 * x^2";
    for (int k = 0; k < 450; ++k) moderate += " + 0.001 * sin(y)";
    for (const std::string& energy : {std::string(90, '(') + "0.5 * x^2" + std::string(90, ')'), moderate}) {
        const auto [status, message] = load_and_step_on_a_small_stack(with_field_energy(energy));
        EXPECT_EQ(status, STRUCTMD_OK) << message.substr(0, 300);
    }
}

// Two particles on top of each other give infinite or NaN energies, and a term outside its domain
// (log of a negative number) a NaN energy with finite forces: every getter of an energy, the virial
// or the pressure is then STRUCTMD_ERR_NUMERICAL naming it, and writes nothing (issue 37, defect 4).
TEST(BadInputs, NonFiniteEnergiesVirialAndPressureAreNumericalErrors) {
    const double kept = -7.0;  // what the caller's memory held before each call
    const auto numerical_and_unwritten = [&](structmd_sim* sim, const std::string& what,
                                             const std::function<structmd_status(double*)>& get, size_t count) {
        std::vector<double> values(count, kept);
        EXPECT_EQ(get(values.data()), STRUCTMD_ERR_NUMERICAL) << what;
        const std::string message = structmd_last_error(sim);
        EXPECT_NE(message.find(what), std::string::npos) << message;
        EXPECT_NE(message.find("is not finite"), std::string::npos) << message;
        for (double v : values) EXPECT_EQ(v, kept) << what;
    };
    const auto energies_refused = [&](structmd_sim* sim) {
        numerical_and_unwritten(sim, "\"potential\" energy", [&](double* v) { return structmd_get_energy(sim, "potential", v); }, 1);
        numerical_and_unwritten(sim, "\"total\" energy", [&](double* v) { return structmd_get_energy(sim, "total", v); }, 1);
        numerical_and_unwritten(sim, "energy of particle id ",
                                [&](double* v) { return structmd_get_particle_energies(sim, v, 4); }, 4);
    };

    json coincident = json::parse(base_input_text());
    coincident["state"]["data"][2][1] = coincident["state"]["data"][3][1];
    Handle sim(kHandleOptions);
    ASSERT_EQ(structmd_load_string(sim.get(), coincident.dump().c_str()), STRUCTMD_OK) << structmd_last_error(sim.get());
    energies_refused(sim.get());
    numerical_and_unwritten(sim.get(), "virial", [&](double* v) { return structmd_get_virial(sim.get(), v); }, 9);
    numerical_and_unwritten(sim.get(), "pressure", [&](double* v) { return structmd_get_pressure(sim.get(), v); }, 1);

    json outside = json::parse(base_input_text());
    outside["topology"]["forceField"]["field"] = {{"type", {"External", "Expression"}},
                                                  {"parameters", {{"energy", "log(x - 100)"}}}};
    Handle second(kHandleOptions);
    ASSERT_EQ(structmd_load_string(second.get(), outside.dump().c_str()), STRUCTMD_OK) << structmd_last_error(second.get());
    std::vector<double> forces(12);
    EXPECT_EQ(structmd_get_forces(second.get(), forces.data(), 4), STRUCTMD_OK) << structmd_last_error(second.get());
    energies_refused(second.get());
}

TEST(BadInputs, MissingNullAndUnreadableSourcesAreNamed) {
    const std::string good = base_input_text();
    Handle sim(kHandleOptions);
    const std::string missing = "/nonexistent/structmd/input.json";
    EXPECT_EQ(structmd_load_file(sim.get(), missing.c_str()), STRUCTMD_ERR_IO);
    EXPECT_NE(std::string(structmd_last_error(sim.get())).find(missing), std::string::npos) << structmd_last_error(sim.get());
    expect_usable_after_failure(sim.get(), good, std::nullopt);

    EXPECT_EQ(structmd_load_file(sim.get(), nullptr), STRUCTMD_ERR_ARGUMENT);
    EXPECT_EQ(std::string(structmd_last_error(sim.get())).rfind("path: ", 0), 0u) << structmd_last_error(sim.get());
    EXPECT_EQ(structmd_load_string(sim.get(), nullptr), STRUCTMD_ERR_ARGUMENT);
    EXPECT_EQ(std::string(structmd_last_error(sim.get())).rfind("json: ", 0), 0u) << structmd_last_error(sim.get());
    ASSERT_EQ(structmd_load_string(sim.get(), good.c_str()), STRUCTMD_OK) << structmd_last_error(sim.get());
    EXPECT_EQ(structmd_step(sim.get(), 10), STRUCTMD_OK) << structmd_last_error(sim.get());

    // Without a handle the message is kept for this thread.
    EXPECT_EQ(structmd_load_string(nullptr, good.c_str()), STRUCTMD_ERR_ARGUMENT);
    EXPECT_EQ(std::string(structmd_last_error(nullptr)).rfind("sim: ", 0), 0u) << structmd_last_error(nullptr);
    EXPECT_EQ(structmd_load_file(nullptr, missing.c_str()), STRUCTMD_ERR_ARGUMENT);
}

// Misuse the header forbids: the handle's memory is freed, so what follows reads freed memory on
// purpose. Before the memory is reused, the mark destroy leaves turns a second destroy (which was
// SIGABRT) and a step (SIGSEGV) into a refusal. AddressSanitizer rightly reports the read itself.
#if defined(__SANITIZE_ADDRESS__)
#define STRUCTMD_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define STRUCTMD_UNDER_ASAN 1
#endif
#endif
TEST(BadInputs, AHandleUsedAfterDestroyIsRefusedWhileItsMemoryIsNotReused) {
#ifdef STRUCTMD_UNDER_ASAN
    GTEST_SKIP() << "reads freed memory on purpose";
#endif
    const std::string good = base_input_text();
    structmd_sim* sim = nullptr;
    ASSERT_EQ(structmd_create(kHandleOptions, &sim), STRUCTMD_OK) << structmd_last_error(nullptr);
    ASSERT_EQ(structmd_load_string(sim, good.c_str()), STRUCTMD_OK) << structmd_last_error(sim);
    structmd_destroy(sim);
    EXPECT_EQ(structmd_step(sim, 1), STRUCTMD_ERR_ARGUMENT);
    EXPECT_EQ(std::string(structmd_last_error(nullptr)), "sim: not a live handle (destroyed already?)");
    EXPECT_EQ(std::string(structmd_last_error(sim)), "sim: not a live handle (destroyed already?)");
    structmd_destroy(sim);
    EXPECT_EQ(std::string(structmd_last_error(nullptr)), "structmd_destroy: sim: not a live handle (destroyed already?)");
}

}  // namespace
