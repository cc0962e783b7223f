// displaced() (integrators/integrator.hpp), every integrator's drift: the wrapped position plus the
// image times the box is where the particle went, over moves that cross the box once, several times
// or not at all, and an image at the limit of an int stays there.
#include <gtest/gtest.h>

#include <random>

#include "integrators/integrator.hpp"

namespace structmd {
namespace {

TEST(Displaced, WrappedPositionAndImageTogetherAreWhereTheParticleWent) {
    const Box<double> box = Box<double>::make(10.0, 12.0, 14.0);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> inside(-0.5, 0.5), small(-0.6, 0.6), large(-30.0, 30.0);
    int crossings = 0, stays = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Real4<double> start{inside(random) * 10.0, inside(random) * 12.0, inside(random) * 14.0, 3.0};
        const Vec3<double> move = trial % 2 ? Vec3<double>{small(random), small(random), small(random)}
                                            : Vec3<double>{large(random), large(random), large(random)};
        const Image before{trial, -2 * trial, 7};
        Image image = before;
        const Real4<double> end = displaced(start, move, box, image);
        EXPECT_EQ(end.w, 3.0) << "the type stays";
        EXPECT_TRUE(end.x >= -5.0 && end.x < 5.0 && end.y >= -6.0 && end.y < 6.0 && end.z >= -7.0 && end.z < 7.0);
        EXPECT_NEAR(end.x + 10.0 * (image.x - before.x), start.x + move.x, 1e-12);
        EXPECT_NEAR(end.y + 12.0 * (image.y - before.y), start.y + move.y, 1e-12);
        EXPECT_NEAR(end.z + 14.0 * (image.z - before.z), start.z + move.z, 1e-12);
        const bool crossed = image.x != before.x || image.y != before.y || image.z != before.z;
        crossings += crossed;
        stays += !crossed;
    }
    EXPECT_GT(crossings, 500);
    EXPECT_GT(stays, 200);
}

TEST(Displaced, AnImageAtTheLimitOfAnIntSaturates) {
    const Box<double> box = Box<double>::make(10.0, 10.0, 10.0);
    Image image{2147483647, -2147483647, 0};
    const Real4<double> end = displaced(Real4<double>{4.9, -4.9, 0.0, 0.0}, Vec3<double>{0.2, -0.2, 0.0}, box, image);
    EXPECT_NEAR(end.x, -4.9, 1e-12);
    EXPECT_NEAR(end.y, 4.9, 1e-12);
    EXPECT_EQ(image.x, 2147483647);
    EXPECT_EQ(image.y, -2147483647);
    EXPECT_EQ(image.z, 0);
}

}  // namespace
}  // namespace structmd
