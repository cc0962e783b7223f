// The pieces of the hydrodynamic integrators below the engine: the dense RPY mobility against its
// matrix-free product, the CPU backend's Cholesky factorisation (and its refusal of a matrix that is
// not positive definite), the Lanczos square root against the symmetric square root from a full
// eigendecomposition, and the fault word that carries a failed factorisation to the host.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "backends/cpu/cpu_cholesky.hpp"
#include "core/error.hpp"
#include "hydrodynamics/lanczos_sqrt.hpp"
#include "hydrodynamics/open_mobility.hpp"
#include "state/fault.hpp"

namespace structmd {
namespace {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// n spheres of radii 0.5 and 1 in a cube of side `side`: dense enough that many overlap.
std::vector<Real4<double>> random_spheres(int n, double side, unsigned seed) {
    std::mt19937 engine(seed);
    std::uniform_real_distribution<double> coordinate(-side / 2, side / 2);
    std::vector<Real4<double>> spheres(n);
    for (int i = 0; i < n; ++i)
        spheres[i] = {coordinate(engine), coordinate(engine), coordinate(engine), i % 2 ? 1.0 : 0.5};
    return spheres;
}

struct Fixture {
    CpuBackend backend{1};
    RpyTensor<double> rpy{1.0 / 0.8};
    HostBuffer<Real4<double>> spheres;

    explicit Fixture(const std::vector<Real4<double>>& given) { backend.upload(spheres, given.data(), given.size()); }
    int64_t count() const { return static_cast<int64_t>(spheres.size()); }

    Matrix dense() {
        const int64_t rows = 3 * count();
        HostBuffer<double> matrix;
        backend.resize(matrix, static_cast<size_t>(rows * rows));
        backend.for_each(count() * count(), FillDenseMobility<double>{spheres.data(), count(), rpy, matrix.data()});
        return Eigen::Map<Matrix>(matrix.data(), rows, rows);
    }
    void product(const double* v, double* out) const {
        backend.for_each_lanes(count(), MobilityProduct<double>{spheres.data(), count(), rpy, v, out});
    }
};

Vector gaussian_vector(int64_t n, unsigned seed) {
    std::mt19937 engine(seed);
    std::normal_distribution<double> normal;
    Vector z(n);
    for (int64_t i = 0; i < n; ++i) z[i] = normal(engine);
    return z;
}

Vector symmetric_sqrt_times(const Matrix& m, const Vector& z) {
    Eigen::SelfAdjointEigenSolver<Matrix> eigen(m);
    return eigen.eigenvectors() * eigen.eigenvalues().cwiseSqrt().asDiagonal() * eigen.eigenvectors().transpose() * z;
}

TEST(OpenMobility, DenseMatrixIsSymmetricPositiveDefiniteAndMatchesTheMatrixFreeProduct) {
    Fixture f(random_spheres(12, 3.0, 1));
    const Matrix m = f.dense();
    EXPECT_LT((m - m.transpose()).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix>(m).eigenvalues().minCoeff(), 0.0);
    const Vector v = gaussian_vector(m.rows(), 2);
    Vector out(m.rows());
    f.product(v.data(), out.data());
    EXPECT_LT((out - m * v).norm(), 1e-13 * (m * v).norm());
}

TEST(OpenMobility, ParticlesOutsideTheGroupAreDecoupled) {
    std::vector<Real4<double>> spheres = random_spheres(4, 1.5, 3);
    spheres[2].w = 0.0;
    Fixture f(spheres);
    const Matrix m = f.dense();
    for (int a = 0; a < 12; ++a)
        for (int b = 6; b < 9; ++b) {
            EXPECT_EQ(m(a, b), a == b ? 1.0 : 0.0);
            EXPECT_EQ(m(b, a), a == b ? 1.0 : 0.0);
        }
    Vector v = Vector::Ones(12), out(12);
    f.product(v.data(), out.data());
    EXPECT_EQ(out.segment(6, 3).norm(), 0.0);
}

TEST(CpuCholesky, FactorsTheMobility) {
    Fixture f(random_spheres(10, 2.5, 4));
    const Matrix m = f.dense();
    Matrix factored = m;
    int failed = -1;
    CpuCholesky<double>(f.backend, m.rows()).factor(factored.data(), &failed);
    ASSERT_EQ(failed, 0);
    const Matrix l = factored.triangularView<Eigen::Lower>();
    EXPECT_LT((l * l.transpose() - m).cwiseAbs().maxCoeff(), 1e-14 * m.cwiseAbs().maxCoeff());
}

TEST(CpuCholesky, ReportsAMatrixThatIsNotPositiveDefinite) {
    Matrix m = Matrix::Identity(4, 4);
    m(1, 2) = m(2, 1) = 2.0;  // eigenvalues 3 and -1 in that block
    int failed = -1;
    CpuCholesky<double>(CpuBackend{1}, 4).factor(m.data(), &failed);
    EXPECT_EQ(failed, 1);
}

TEST(LanczosSqrt, ApproachesTheSymmetricSquareRootToTheTolerance) {
    Fixture f(random_spheres(20, 3.0, 5));
    const Matrix m = f.dense();
    const Vector z = gaussian_vector(m.rows(), 6);
    const Vector exact = symmetric_sqrt_times(m, z);
    for (double tolerance : {1e-3, 1e-6, 1e-10}) {
        LanczosSqrt<CpuBackend, double> lanczos(f.backend, tolerance, 100, "the test operator");
        Vector y(m.rows());
        const int iterations = lanczos.apply_sqrt(m.rows(), z.data(), y.data(),
                                                  [&](const double* v, double* out) { f.product(v, out); });
        const double error = (y - exact).norm() / exact.norm();
        // The stopping rule measures the last change, which bounds the error within a small factor.
        EXPECT_LT(error, 10.0 * tolerance) << "tolerance " << tolerance << ", " << iterations << " iterations";
        EXPECT_LT(iterations, m.rows());
    }
}

TEST(LanczosSqrt, IsExactOnceTheKrylovSpaceIsExhausted) {
    Fixture f(random_spheres(2, 1.0, 7));
    const Matrix m = f.dense();
    const Vector z = gaussian_vector(6, 8);
    LanczosSqrt<CpuBackend, double> lanczos(f.backend, 1e-300, 100, "the test operator");
    Vector y(6);
    EXPECT_LE(lanczos.apply_sqrt(6, z.data(), y.data(), [&](const double* v, double* out) { f.product(v, out); }), 6);
    EXPECT_LT((y - symmetric_sqrt_times(m, z)).norm(), 1e-12 * z.norm());
}

TEST(LanczosSqrt, RefusesAnOperatorThatIsNotPositiveDefinite) {
    CpuBackend backend{1};
    const Vector diagonal = (Vector(5) << 1.0, 2.0, -3.0, 4.0, 5.0).finished();
    const Vector z = Vector::Ones(5);
    Vector y(5);
    LanczosSqrt<CpuBackend, double> lanczos(backend, 1e-8, 100, "the test operator");
    try {
        lanczos.apply_sqrt(5, z.data(), y.data(), [&](const double* v, double* out) {
            for (int i = 0; i < 5; ++i) out[i] = diagonal[i] * v[i];
        });
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), STRUCTMD_ERR_NUMERICAL);
        EXPECT_NE(std::string(e.what()).find("the test operator is not positive definite"), std::string::npos);
    }
}

TEST(FaultSlot, CarriesAFailedFactorisationWithTheParticleAndStep) {
    unsigned long long word = kNoFault;
    StepClock clock{};
    clock.step = 4321;
    FaultSlot slot{&word, ClockView{&clock}, 1.0};
    slot.report(123456789, FaultQuantity::mobility);
    EXPECT_EQ(FaultSlot::particle_of(word), 123456789);
    EXPECT_EQ(FaultSlot::quantity_of(word), FaultQuantity::mobility);
    EXPECT_EQ(FaultSlot::step_of(word), 4321);
}

}  // namespace
}  // namespace structmd
