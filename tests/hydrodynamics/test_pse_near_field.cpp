// The near-field tensor of the positively split Ewald method (hydrodynamics/pse_near_field.hpp):
// with the far field's real-space image, computed here by quadrature of its Fourier multiplier, it
// must give the free-space RPY tensor (overlapping and not); it is continuous at contact and where
// its small-r expansion takes over, and below the tolerance beyond its cutoff.
#include <gtest/gtest.h>

#include <cmath>

#include "hydrodynamics/pse_near_field.hpp"

namespace structmd {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Split {
    double radius, xi, viscosity;
    PseNearTensor<double> tensor(double tolerance = 1e-6) const {
        return make_pse_near_tensor<double>(radius, xi, viscosity, tolerance);
    }
    double mu0() const { return 1.0 / (6.0 * kPi * viscosity * radius); }
};

// The far field's real-space tensor in free space, (transverse, longitudinal):
//   M_far(r) = (2 pi)^-3 int d^3k H(k) (I - k^ k^) exp(i k.r),
//   H = (sin(k a)/(k a))^2 (1 + k^2/(4 xi^2)) exp(-k^2/(4 xi^2)) / (eta k^2),
// whose angular integrals leave (1 / (2 pi^2)) int k^2 H(k) w(k r) dk with w = j0 - j1/x
// (transverse) and 2 j1/x (longitudinal); Simpson's rule on [0, 14 xi].
void far_field(const Split& s, double r, double& transverse, double& longitudinal) {
    const int intervals = 40000;
    const double top = 14.0 * s.xi, h = top / intervals;
    // At k = 0, k^2 H = 1 / eta and both weights are 2/3.
    transverse = longitudinal = h / 3.0 * (2.0 / 3.0) / s.viscosity;
    for (int i = 1; i <= intervals; ++i) {
        const double k = i * h, x = k * r, ka = k * s.radius;
        const double sinc = std::sin(ka) / ka;
        const double weight = (i == intervals ? 1.0 : (i % 2 ? 4.0 : 2.0)) * h / 3.0;
        const double kernel = k * k * sinc * sinc * (1.0 + k * k / (4.0 * s.xi * s.xi)) *
                              std::exp(-k * k / (4.0 * s.xi * s.xi)) / (s.viscosity * k * k);
        double j1OverX, w;  // j1(x)/x and j0 - j1/x, by series where x is small
        if (x < 1e-3) {
            j1OverX = 1.0 / 3.0 - x * x / 30.0;
            w = 2.0 / 3.0 - 2.0 * x * x / 15.0;
        } else {
            const double j0 = std::sin(x) / x, j1 = std::sin(x) / (x * x) - std::cos(x) / x;
            j1OverX = j1 / x;
            w = j0 - j1OverX;
        }
        transverse += weight * kernel * w;
        longitudinal += weight * kernel * 2.0 * j1OverX;
    }
    transverse /= 2.0 * kPi * kPi;
    longitudinal /= 2.0 * kPi * kPi;
}

// The free-space RPY tensor of equal spheres, (transverse, longitudinal).
void rpy(const Split& s, double r, double& transverse, double& longitudinal) {
    const double a = s.radius;
    if (r > 2.0 * a) {
        transverse = (1.0 + 2.0 * a * a / (3.0 * r * r)) / (8.0 * kPi * s.viscosity * r);
        longitudinal = (1.0 - 2.0 * a * a / (3.0 * r * r)) / (4.0 * kPi * s.viscosity * r);
    } else {
        transverse = s.mu0() * (1.0 - 9.0 * r / (32.0 * a));
        longitudinal = s.mu0() * (1.0 - 3.0 * r / (16.0 * a));
    }
}

TEST(PseNearField, WithTheFarFieldItIsTheRpyTensorOverlappingOrNot) {
    for (const Split& s : {Split{1.0, 0.5, 1.3}, Split{0.7, 1.4, 0.9}, Split{1.0, 0.2, 1.0}}) {
        const PseNearTensor<double> near = s.tensor();
        double farT, farL;
        far_field(s, 0.0, farT, farL);
        EXPECT_NEAR(near.self() + farT, s.mu0(), 1e-9 * s.mu0());
        for (double r : {1e-4, 0.3, 1.0, 1.7, 1.99, 2.01, 2.6, 4.0}) {
            const double distance = r * s.radius;
            const Vec3<double> fg = near.coefficients(distance);
            double rpyT, rpyL;
            far_field(s, distance, farT, farL);
            rpy(s, distance, rpyT, rpyL);
            EXPECT_NEAR(s.mu0() * fg.x + farT, rpyT, 1e-9 * s.mu0()) << "r/a " << r << " xi " << s.xi;
            EXPECT_NEAR(s.mu0() * fg.y + farL, rpyL, 1e-9 * s.mu0()) << "r/a " << r << " xi " << s.xi;
        }
    }
}

TEST(PseNearField, IsContinuousAtContactAndAtTheSmallDistanceExpansion) {
    for (const Split& s : {Split{1.0, 0.5, 1.0}, Split{0.5, 3.0, 1.0}, Split{2.0, 0.03, 1.0}}) {
        const PseNearTensor<double> near = s.tensor();
        for (double at : {2.0 * s.radius, near.smallDistance}) {
            const Vec3<double> below = near.coefficients(at * (1.0 - 1e-9)), above = near.coefficients(at * (1.0 + 1e-9));
            EXPECT_NEAR(below.x, above.x, 1e-6 * near.selfTransverse) << at;
            EXPECT_NEAR(below.y, above.y, 1e-6 * near.selfTransverse) << at;
        }
        EXPECT_GT(near.smallDistance, 0.0);
        EXPECT_LE(near.smallDistance, s.radius);
    }
}

TEST(PseNearField, TwoParticlesAtOnePointGetTheIsotropicLimit) {
    for (const Split& s : {Split{1.0, 0.5, 1.0}, Split{0.5, 3.0, 1.0}}) {
        const PseNearTensor<double> near = s.tensor();
        const Vec3<double> v{0.3, -1.1, 0.7};
        const Vec3<double> atZero = near.apply(Vec3<double>{0.0, 0.0, 0.0}, v);
        const Vec3<double> nearZero = near.apply(Vec3<double>{1e-9, 0.0, 0.0}, v);
        for (const double c : {atZero.x, atZero.y, atZero.z}) EXPECT_TRUE(std::isfinite(c));
        EXPECT_NEAR(atZero.x, nearZero.x, 1e-6 * std::fabs(nearZero.x));
        EXPECT_NEAR(atZero.y, nearZero.y, 1e-6 * std::fabs(nearZero.y));
        EXPECT_NEAR(atZero.z, nearZero.z, 1e-6 * std::fabs(nearZero.z));
    }
}

TEST(PseNearField, FallsBelowTheToleranceBeyondItsCutoff) {
    for (double tolerance : {1e-2, 1e-4, 1e-8})
        for (const Split& s : {Split{1.0, 0.5, 1.0}, Split{0.5, 4.0, 1.0}, Split{1.0, 0.1, 1.0}}) {
            const PseNearTensor<double> near = s.tensor(tolerance);
            const double cutoff = std::sqrt(near.cutoff2);
            for (double r = cutoff; r < 3.0 * cutoff; r += 0.01 * cutoff) {
                const Vec3<double> fg = near.coefficients(r);
                EXPECT_LT(std::fabs(fg.x), tolerance) << r;
                EXPECT_LT(std::fabs(fg.y), tolerance) << r;
            }
            // Beyond the cutoff the product is cut: nothing of it is left.
            const Vec3<double> beyond = near.apply(Vec3<double>{cutoff * 1.001, 0.0, 0.0}, Vec3<double>{1.0, 1.0, 1.0});
            EXPECT_EQ(beyond.x, 0.0);
            // Where UAMMD cuts (sqrt(-ln tol) / xi, when beyond contact) the field is not yet below tolerance.
            const double uammdCut = std::sqrt(-std::log(tolerance)) / s.xi;
            if (s.xi == 0.5 && uammdCut > 2.0 * s.radius) EXPECT_GT(std::fabs(near.coefficients(uammdCut).x), 0.5 * tolerance);
        }
}

}  // namespace
}  // namespace structmd
