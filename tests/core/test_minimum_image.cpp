// Box::minimum_image, which every pair kernel and list build takes a separation through: for the
// difference of two wrapped positions, the image nearest the origin, d or d -+ L rounded once (as
// the subtraction itself rounds), in float and double; along an open axis, d itself.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/box.hpp"

namespace structmd {
namespace {

template <class R>
void expect_nearest_images(const Box<R>& box, int seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> inside(-0.5, 0.5);
    const R lengths[3] = {box.length.x, box.length.y, box.length.z};
    int folded = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        Vec3<R> a, b;
        R* pa[3] = {&a.x, &a.y, &a.z};
        R* pb[3] = {&b.x, &b.y, &b.z};
        for (int axis = 0; axis < 3; ++axis) {
            const double scale = std::isinf(static_cast<double>(lengths[axis])) ? 40.0 : static_cast<double>(lengths[axis]);
            *pa[axis] = R(inside(random) * scale);
            *pb[axis] = R(inside(random) * scale);
        }
        const Vec3<R> d = b - a;
        const Vec3<R> image = box.minimum_image(d);
        const R raw[3] = {d.x, d.y, d.z}, got[3] = {image.x, image.y, image.z};
        for (int axis = 0; axis < 3; ++axis) {
            const R length = lengths[axis];
            if (std::isinf(static_cast<double>(length))) {
                EXPECT_EQ(got[axis], raw[axis]) << "an open axis has no images";
                continue;
            }
            // Near +-L/2 either image is the nearest; a cutoff is shorter than L/2.
            if (std::abs(std::abs(static_cast<double>(raw[axis])) - 0.5 * length) < 1e-5 * length) continue;
            const R expected = 2 * raw[axis] >= length ? raw[axis] - length
                                                       : (2 * raw[axis] < -length ? raw[axis] + length : raw[axis]);
            EXPECT_EQ(got[axis], expected) << "axis " << axis << ", d = " << raw[axis];
            folded += got[axis] != raw[axis];
        }
    }
    EXPECT_GT(folded, 1000) << "the trials were meant to cross the boundary often";
}

TEST(MinimumImage, NearestImageRoundedOnceInFloatAndDouble) {
    expect_nearest_images(Box<double>::make(10.0, 12.5, 7.3), 3);
    expect_nearest_images(Box<float>::make(10.0, 12.5, 7.3), 4);
    expect_nearest_images(Box<double>::make(1.0e4, 3.0, 0.7), 5);
    expect_nearest_images(Box<float>::make(1.0e4, 3.0, 0.7), 6);
}

TEST(MinimumImage, OpenAxesKeepTheSeparation) {
    const double open = std::numeric_limits<double>::infinity();
    expect_nearest_images(Box<double>::make(open, 12.5, open), 7);
    expect_nearest_images(Box<float>::make(9.0, open, open), 8);
}

}  // namespace
}  // namespace structmd
