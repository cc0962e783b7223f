// libFuzzer target: the input bytes choose a sequence of API calls on two handle slots: create (good
// and bad options), load (small valid inputs, junk, missing files), step, run, compute, every getter
// and setter with right and wrong counts, NULL pointers and non-finite values, energies of odd names,
// info and counters into short buffers, checkpoints saved and loaded (also from junk files), destroy.
// Besides the contract of fuzz_contract.hpp, a failed getter must leave the caller's array untouched.
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "fuzz_contract.hpp"

namespace {

using structmd::fuzz::breach;
using structmd::fuzz::checked;

// Four particles: Lennard-Jones, a bond and an angle; 40 steps of velocity Verlet, so run() ends soon.
const char* const kSmallInput = R"({
  "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "fuzz", "seed": 3}}},
  "global": {"types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                       "data": [["A", 1.0, 0.5, 0.0], ["B", 2.0, 0.5, 0.0]]},
             "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[8.0, 8.0, 8.0], 1.0]]}},
  "state": {"labels": ["id", "position"], "data": [[0, [0, 0, 0]], [1, [1.1, 0, 0]], [2, [1.6, 1.0, 0]], [3, [-3, 0.3, -1.2]]]},
  "topology": {"structure": {"labels": ["id", "type"], "data": [[0, "A"], [1, "A"], [2, "B"], [3, "A"]]},
    "forceField": {
      "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},
      "lj": {"type": ["NonBonded", "LennardJonesType1"], "parameters": {"cutOffFactor": 2.5, "condition": "all"},
             "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["A", "A", 1, 1], ["A", "B", 1, 1], ["B", "B", 1, 1]]},
      "bonds": {"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"], "data": [[0, 1, 100, 1]]},
      "angles": {"type": ["Bond3", "HarmonicAngular"], "labels": ["id_i", "id_j", "id_k", "K", "theta0"], "data": [[0, 1, 2, 10, 2]]}}},
  "integrator": {"vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.002}},
                 "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"], "data": [[1, "vv", 40]]}}
})";

// Two bonded particles under Langevin noise, with batches; another particle count than kSmallInput,
// so a checkpoint of one does not fit the other.
const char* const kDimerInput = R"({
  "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "dimer"}}},
  "global": {"types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": [["A", 1.0, 0.5, 0.0]]},
             "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[6.0, 6.0, 6.0], 1.0]]},
             "fundamental": {"type": ["Fundamental", "Time"], "parameters": {"currentStep": 5}}},
  "state": {"labels": ["id", "position"], "data": [[0, [0, 0, 0]], [1, [0.5, -0.6, 0.7]]]},
  "topology": {"structure": {"labels": ["id", "type", "batchId"], "data": [[0, "A", 0], [1, "A", 1]]},
    "forceField": {"bond": {"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"], "data": [[0, 1, 50, 1]]}}},
  "integrator": {"bbk": {"type": ["Langevin", "BBK"], "parameters": {"timeStep": 0.001, "frictionConstant": 1.0}},
                 "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"], "data": [[1, "bbk", 30]]}}
})";

const char* const kCreateOptions[] = {
    structmd::fuzz::kHandleOptions,
    R"({"backend": "cpu", "threads": 1, "precision": "double", "log": "quiet"})",
    nullptr,
    "",
    "{",
    R"({"backend": "cpu", "threads": 0})",
    R"({"backend": "cuda"})",
    R"({"colour": "blue"})",
    R"({"backend": "cpu", "threads": 1, "log": "quiet", "log_file": "/nonexistent/dir/log.txt"})",
};

const char* const kEnergyTerms[] = {"potential", "kinetic", "total", "lj", "bonds", "bond", "angles", "nl",
                                    "potential@batch:0", "kinetic@batch:1", "lj@batch:7", "potential@batch:-1",
                                    "potential@batch:99999999999999999999", "total@batch:", "@batch:0", ""};

constexpr double kSentinel = -12345.678;

template <class T>
T pick(FuzzedDataProvider& in, const T* choices, size_t count) {
    return choices[in.ConsumeIntegralInRange<size_t>(0, count - 1)];
}

// The count a getter or setter is given: the right one, one off, zero, negative or anything.
int64_t pick_count(FuzzedDataProvider& in, int64_t particles) {
    switch (in.ConsumeIntegralInRange(0, 4)) {
        case 0: return particles;
        case 1: return particles + (in.ConsumeBool() ? 1 : -1);
        case 2: return 0;
        case 3: return -in.ConsumeIntegralInRange<int64_t>(1, INT64_MAX);
        default: return in.ConsumeIntegralInRange<int64_t>(0, 64);
    }
}

int64_t particles_of(structmd_sim* sim) {
    int64_t n = 0;
    return sim && structmd_get_num_particles(sim, &n) == STRUCTMD_OK ? n : 0;
}

class Session {
public:
    explicit Session(FuzzedDataProvider& in) : in_(in) {
        const std::string stem = "fuzz_api_sequence_" + std::to_string(::getpid());
        checkpoint_ = stem + ".chk";
        junk_ = stem + ".junk";
        document_ = stem + ".json";
        remove_files();
    }
    ~Session() {
        for (structmd_sim*& sim : slots_) structmd_destroy(sim);
        remove_files();
    }

    void one_call() {
        structmd_sim*& sim = slots_[in_.ConsumeIntegralInRange(0, 1)];
        switch (in_.ConsumeIntegralInRange(0, 17)) {
            case 0: create(sim); break;
            case 1: structmd_destroy(sim); sim = nullptr; break;
            case 2: checked("structmd_load_string", structmd_load_string(sim, pick_document().c_str()), sim); break;
            case 3: load_file(sim); break;
            case 4: checked("structmd_step", structmd_step(sim, in_.ConsumeIntegralInRange<int64_t>(-3, 50)), sim); break;
            case 5: checked("structmd_run", structmd_run(sim), sim); break;
            case 6: checked("structmd_compute", structmd_compute(sim, in_.ConsumeIntegralInRange<uint32_t>(0, 15)), sim); break;
            case 7: get_vectors(sim); break;
            case 8: get_scalars(sim); break;
            case 9: set_vectors(sim); break;
            case 10: set_box(sim); break;
            case 11: get_energy(sim); break;
            case 12: get_small_values(sim); break;
            case 13: get_info(sim); break;
            case 14: get_counters(sim); break;
            case 15: checked("structmd_save_checkpoint", structmd_save_checkpoint(sim, pick_checkpoint_path()), sim); break;
            case 16: load_checkpoint(sim); break;
            default: structmd_last_error(sim); break;
        }
    }

private:
    void create(structmd_sim*& sim) {
        structmd_destroy(sim);
        sim = nullptr;
        const char* options = pick(in_, kCreateOptions, std::size(kCreateOptions));
        const structmd_status status = checked("structmd_create", structmd_create(options, &sim), nullptr);
        if ((status == STRUCTMD_OK) != (sim != nullptr)) breach("structmd_create", status, "handle and status disagree", "");
    }

    std::string pick_document() {
        switch (in_.ConsumeIntegralInRange(0, 3)) {
            case 0: return kSmallInput;
            case 1: return kDimerInput;
            case 2: return std::string(kSmallInput).substr(0, in_.ConsumeIntegralInRange<size_t>(0, 200));
            default: return in_.ConsumeRandomLengthString(256);
        }
    }

    void load_file(structmd_sim* sim) {
        if (in_.ConsumeBool()) {
            checked("structmd_load_file", structmd_load_file(sim, in_.ConsumeBool() ? nullptr : "/nonexistent.json"), sim);
            return;
        }
        if (std::FILE* file = std::fopen(document_.c_str(), "wb")) {
            const std::string text = pick_document();
            std::fwrite(text.data(), 1, text.size(), file);
            std::fclose(file);
        }
        checked("structmd_load_file", structmd_load_file(sim, document_.c_str()), sim);
    }

    // Fills a caller's array with a sentinel and checks that a failed call left every element so.
    template <class T, class Call>
    void read_array(const char* name, structmd_sim* sim, size_t perParticle, Call call) {
        const int64_t n = pick_count(in_, particles_of(sim));
        const bool null = in_.ConsumeIntegralInRange(0, 7) == 0;
        std::vector<T> buffer(n > 0 && n <= (1 << 16) ? static_cast<size_t>(n) * perParticle : 0, static_cast<T>(kSentinel));
        const structmd_status status = checked(name, call(sim, null ? nullptr : buffer.data(), n), sim);
        if (status == STRUCTMD_OK) return;
        for (const T& value : buffer)
            if (value != static_cast<T>(kSentinel)) breach(name, status, "wrote into the caller's array and failed", structmd_last_error(sim));
    }

    void get_vectors(structmd_sim* sim) {
        switch (in_.ConsumeIntegralInRange(0, 2)) {
            case 0: read_array<double>("structmd_get_positions", sim, 3, structmd_get_positions); break;
            case 1: read_array<double>("structmd_get_velocities", sim, 3, structmd_get_velocities); break;
            default: read_array<double>("structmd_get_forces", sim, 3, structmd_get_forces); break;
        }
    }

    void get_scalars(structmd_sim* sim) {
        switch (in_.ConsumeIntegralInRange(0, 3)) {
            case 0: read_array<double>("structmd_get_particle_energies", sim, 1, structmd_get_particle_energies); break;
            case 1: read_array<double>("structmd_get_masses", sim, 1, structmd_get_masses); break;
            case 2: read_array<int32_t>("structmd_get_types", sim, 1, structmd_get_types); break;
            default: read_array<int64_t>("structmd_get_ids", sim, 1, structmd_get_ids); break;
        }
    }

    // Any double the bytes spell: NaN, infinities and huge values included.
    std::vector<double> values(size_t count) {
        std::vector<double> result(count);
        const double scale = in_.ConsumeFloatingPoint<double>();
        for (size_t i = 0; i < count; ++i)
            result[i] = in_.remaining_bytes() >= sizeof(double) ? in_.ConsumeFloatingPoint<double>() : scale * double(i % 7);
        return result;
    }

    void set_vectors(structmd_sim* sim) {
        const int64_t n = pick_count(in_, particles_of(sim));
        const bool null = in_.ConsumeIntegralInRange(0, 7) == 0;
        std::vector<double> v = values(n > 0 && n <= (1 << 16) ? 3 * static_cast<size_t>(n) : 0);
        const double* data = null ? nullptr : v.data();
        switch (in_.ConsumeIntegralInRange(0, 2)) {
            case 0: checked("structmd_set_positions", structmd_set_positions(sim, data, n), sim); break;
            case 1: checked("structmd_set_velocities", structmd_set_velocities(sim, data, n), sim); break;
            default: checked("structmd_set_external_forces", structmd_set_external_forces(sim, data, n), sim); break;
        }
    }

    void set_box(structmd_sim* sim) {
        std::array<double, 3> lengths{};
        for (double& length : lengths) length = in_.ConsumeFloatingPoint<double>();
        checked("structmd_set_box", structmd_set_box(sim, in_.ConsumeBool() ? nullptr : lengths.data()), sim);
    }

    void get_energy(structmd_sim* sim) {
        const std::string random = in_.ConsumeRandomLengthString(32);
        const int choice = in_.ConsumeIntegralInRange(0, 2);
        const char* term = choice == 0 ? pick(in_, kEnergyTerms, std::size(kEnergyTerms)) : choice == 1 ? random.c_str() : nullptr;
        double value = kSentinel;
        const structmd_status status =
            checked("structmd_get_energy", structmd_get_energy(sim, term, in_.ConsumeBool() ? &value : nullptr), sim);
        if (status != STRUCTMD_OK && value != kSentinel) breach("structmd_get_energy", status, "wrote a value and failed", structmd_last_error(sim));
    }

    void get_small_values(structmd_sim* sim) {
        const bool null = in_.ConsumeIntegralInRange(0, 3) == 0;
        std::array<double, 9> out{};
        int64_t integer = 0;
        switch (in_.ConsumeIntegralInRange(0, 5)) {
            case 0: checked("structmd_get_virial", structmd_get_virial(sim, null ? nullptr : out.data()), sim); break;
            case 1: checked("structmd_get_pressure", structmd_get_pressure(sim, null ? nullptr : out.data()), sim); break;
            case 2: checked("structmd_get_box", structmd_get_box(sim, null ? nullptr : out.data()), sim); break;
            case 3: checked("structmd_get_step", structmd_get_step(sim, null ? nullptr : &integer), sim); break;
            case 4: checked("structmd_get_time", structmd_get_time(sim, null ? nullptr : out.data()), sim); break;
            default: checked("structmd_get_num_particles", structmd_get_num_particles(sim, null ? nullptr : &integer), sim); break;
        }
    }

    void get_info(structmd_sim* sim) {
        const size_t size = in_.ConsumeIntegralInRange<size_t>(0, 400);
        std::vector<char> buffer(size);
        size_t needed = 0;
        const bool nullBuffer = in_.ConsumeIntegralInRange(0, 3) == 0;
        checked("structmd_get_info",
                structmd_get_info(sim, nullBuffer ? nullptr : buffer.data(), size, in_.ConsumeBool() ? &needed : nullptr), sim);
    }

    void get_counters(structmd_sim* sim) {
        const size_t size = in_.ConsumeIntegralInRange<size_t>(0, 600);
        std::vector<char> buffer(size);
        checked("structmd_get_counters", structmd_get_counters(sim, in_.ConsumeIntegralInRange(0, 3) == 0 ? nullptr : buffer.data(), size), sim);
    }

    const char* pick_checkpoint_path() {
        switch (in_.ConsumeIntegralInRange(0, 3)) {
            case 0: return nullptr;
            case 1: return "/nonexistent/dir/state.chk";
            default: return checkpoint_.c_str();
        }
    }

    void load_checkpoint(structmd_sim* sim) {
        if (in_.ConsumeBool()) {
            // A junk file: what remains of the input, or a saved checkpoint with some bytes changed.
            std::string bytes = in_.ConsumeRandomLengthString(512);
            if (std::FILE* saved = std::fopen(checkpoint_.c_str(), "rb"); saved && in_.ConsumeBool()) {
                std::vector<char> content(1 << 16);
                content.resize(std::fread(content.data(), 1, content.size(), saved));
                for (size_t i = 0; i < bytes.size() && !content.empty(); ++i) content[(i * 131u) % content.size()] ^= bytes[i];
                bytes.assign(content.begin(), content.end());
                std::fclose(saved);
            } else if (saved) {
                std::fclose(saved);
            }
            if (std::FILE* file = std::fopen(junk_.c_str(), "wb")) {
                std::fwrite(bytes.data(), 1, bytes.size(), file);
                std::fclose(file);
            }
            checked("structmd_load_checkpoint", structmd_load_checkpoint(sim, junk_.c_str()), sim);
            return;
        }
        checked("structmd_load_checkpoint", structmd_load_checkpoint(sim, pick_checkpoint_path()), sim);
    }

    void remove_files() {
        std::remove(checkpoint_.c_str());
        std::remove((checkpoint_ + ".tmp").c_str());
        std::remove(junk_.c_str());
        std::remove(document_.c_str());
    }

    FuzzedDataProvider& in_;
    std::array<structmd_sim*, 2> slots_{};
    std::string checkpoint_, junk_, document_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzedDataProvider in(data, size);
    Session session(in);
    for (int call = 0; call < 64 && in.remaining_bytes() > 0; ++call) session.one_call();
    return 0;
}
