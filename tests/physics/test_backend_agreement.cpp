// CUDA against CPU on the lj_bonds reference case, and on the Surface walls' cases (surfaces,
// plain_cylinder: the per-type external kernel): forces after loading, and positions after a short
// trajectory from the same velocities. Exits with 77 (skipped for CTest) when no CUDA backend is usable.
#include "physics_support.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace structmd_physics {
namespace {

std::string case_path(const std::string& name) {
    return std::string(STRUCTMD_REFERENCE_DATA_DIR) + "/" + name + ".json";
}

SimHandle load_case(const std::string& name, const std::string& backend, const std::string& precision) {
    structmd_sim* raw = nullptr;
    if (structmd_create(create_options(backend, precision).c_str(), &raw) != STRUCTMD_OK) {
        ADD_FAILURE() << backend << "/" << precision << ": " << structmd_last_error(nullptr);
        return nullptr;
    }
    SimHandle sim(raw);
    if (structmd_load_file(sim.get(), case_path(name).c_str()) != STRUCTMD_OK) {
        ADD_FAILURE() << backend << "/" << precision << ": " << structmd_last_error(sim.get());
        return nullptr;
    }
    return sim;
}

// Same velocities on both backends (T ~ 1), so that the trajectories are comparable.
std::vector<double> test_velocities(std::int64_t n) {
    SplitMix64 rng(77);
    std::vector<double> v(3 * n);
    for (double& c : v) c = rng.normal();
    return v;
}

struct PrecisionCase {
    std::string name;  // the reference case (tests/reference/data/<name>.json)
    std::string precision;
    double force_tolerance;
    std::int64_t steps;
    double position_tolerance;
};

class BackendAgreement : public ::testing::TestWithParam<PrecisionCase> {};

TEST_P(BackendAgreement, Forces) {
    const PrecisionCase& c = GetParam();
    SimHandle cpu = load_case(c.name, "cpu", c.precision), cuda = load_case(c.name, "cuda", c.precision);
    ASSERT_TRUE(cpu && cuda);
    std::int64_t n = 0;
    ASSERT_STRUCTMD_OK(cpu.get(), structmd_get_num_particles(cpu.get(), &n));
    std::vector<double> f_cpu(3 * n), f_cuda(3 * n);
    ASSERT_STRUCTMD_OK(cpu.get(), structmd_get_forces(cpu.get(), f_cpu.data(), n));
    ASSERT_STRUCTMD_OK(cuda.get(), structmd_get_forces(cuda.get(), f_cuda.data(), n));
    const double deviation = max_relative_deviation(f_cuda, f_cpu);
    std::printf("[ deviation ] cuda vs cpu %s %s forces: %.3e (tolerance %.0e)\n", c.name.c_str(), c.precision.c_str(),
                deviation, c.force_tolerance);
    EXPECT_LT(deviation, c.force_tolerance);
}

// Double: the backends differ by summation order, ~1e-15 relative in the forces; chaotic growth in
// a dense liquid (largest Lyapunov exponent a few per tau) amplifies that by at most ~1e3 over one
// tau (200 steps), leaving positions within ~1e-12, far inside 1e-8. Single: float rounding of the
// positions alone is ~5e-7 per step; 50 steps keep growth small, and 1e-4 sigma is still tiny next to
// the ~0.3 sigma a particle moves, so a wrong kick or a missing term would show. The walls' cases are
// no liquid (the particles do not meet), so nothing amplifies the differences; their fastest particles
// move 0.3 to 1.4 in these steps of 0.001.
TEST_P(BackendAgreement, Trajectory) {
    const PrecisionCase& c = GetParam();
    SimHandle cpu = load_case(c.name, "cpu", c.precision), cuda = load_case(c.name, "cuda", c.precision);
    ASSERT_TRUE(cpu && cuda);
    std::int64_t n = 0;
    ASSERT_STRUCTMD_OK(cpu.get(), structmd_get_num_particles(cpu.get(), &n));
    const std::vector<double> velocities = test_velocities(n);
    std::vector<double> start(3 * n), x_cpu(3 * n), x_cuda(3 * n);
    ASSERT_STRUCTMD_OK(cpu.get(), structmd_get_positions(cpu.get(), start.data(), n));
    for (structmd_sim* sim : {cpu.get(), cuda.get()}) {
        ASSERT_STRUCTMD_OK(sim, structmd_set_velocities(sim, velocities.data(), n));
        ASSERT_STRUCTMD_OK(sim, structmd_step(sim, c.steps));
    }
    ASSERT_STRUCTMD_OK(cpu.get(), structmd_get_positions(cpu.get(), x_cpu.data(), n));
    ASSERT_STRUCTMD_OK(cuda.get(), structmd_get_positions(cuda.get(), x_cuda.data(), n));
    double box[3];
    ASSERT_STRUCTMD_OK(cpu.get(), structmd_get_box(cpu.get(), box));
    double max_difference = 0.0, max_displacement = 0.0;
    for (std::int64_t i = 0; i < 3 * n; ++i) {
        max_difference = std::max(max_difference, std::abs(minimum_image(x_cuda[i] - x_cpu[i], box[i % 3])));
        max_displacement = std::max(max_displacement, std::abs(minimum_image(x_cpu[i] - start[i], box[i % 3])));
    }
    std::printf("[ deviation ] cuda vs cpu %s %s positions after %lld steps: %.3e (tolerance %.0e; max displacement "
                "%.3f)\n",
                c.name.c_str(), c.precision.c_str(), static_cast<long long>(c.steps), max_difference,
                c.position_tolerance, max_displacement);
    EXPECT_GT(max_displacement, 100.0 * c.position_tolerance) << "the particles hardly moved";
    EXPECT_LT(max_difference, c.position_tolerance);
}

INSTANTIATE_TEST_SUITE_P(Precisions, BackendAgreement,
                         ::testing::Values(PrecisionCase{"lj_bonds", "double", 1e-10, 200, 1e-8},
                                           PrecisionCase{"lj_bonds", "mixed", 1e-5, 50, 1e-4},
                                           PrecisionCase{"lj_bonds", "single", 1e-5, 50, 1e-4},
                                           PrecisionCase{"surfaces", "double", 1e-10, 200, 1e-8},
                                           PrecisionCase{"surfaces", "single", 1e-5, 50, 1e-4},
                                           PrecisionCase{"plain_cylinder", "double", 1e-10, 200, 1e-8},
                                           PrecisionCase{"plain_cylinder", "single", 1e-5, 50, 1e-4}),
                         [](const ::testing::TestParamInfo<PrecisionCase>& info) {
                             return info.param.name + "_" + info.param.precision;
                         });

}  // namespace
}  // namespace structmd_physics

int main(int argc, char** argv) { return structmd_physics::run_tests_if_cuda(argc, argv); }
