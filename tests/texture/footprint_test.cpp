// uvFootprint: world widths into uv units through the parameterisation.

#include "strahl/texture/footprint.h"

#include <gtest/gtest.h>

#include <cmath>

namespace strahl {
namespace {

TEST(Footprint, DividesByTheSquareRootOfTheUvArea) {
    // One uv unit spans 2 world units each way: 0.1 world is 0.05 in uv.
    EXPECT_FLOAT_EQ(uvFootprint(0.1f, Vec3(2, 0, 0), Vec3(0, 2, 0)), 0.05f);
    // Stretched 4 x 1: the mean scale, sqrt(4).
    EXPECT_FLOAT_EQ(uvFootprint(1.0f, Vec3(0, 0, 4), Vec3(1, 0, 0)), 0.5f);
    // Sheared: only the area counts.
    EXPECT_FLOAT_EQ(uvFootprint(1.0f, Vec3(1, 0, 0), Vec3(5, 0.25f, 0)), 2.0f);
}

TEST(Footprint, DegenerateInputsGiveTheFinestLevel) {
    EXPECT_EQ(uvFootprint(0.0f, Vec3(1, 0, 0), Vec3(0, 1, 0)), 0.0f);
    EXPECT_EQ(uvFootprint(-1.0f, Vec3(1, 0, 0), Vec3(0, 1, 0)), 0.0f);
    EXPECT_EQ(uvFootprint(std::nanf(""), Vec3(1, 0, 0), Vec3(0, 1, 0)), 0.0f);
    EXPECT_EQ(uvFootprint(1.0f, Vec3(1, 0, 0), Vec3(2, 0, 0)), 0.0f);  // parallel
    EXPECT_EQ(uvFootprint(1.0f, Vec3(0.0f), Vec3(0, 1, 0)), 0.0f);
    EXPECT_EQ(uvFootprint(1.0f, Vec3(kInfinity, 0, 0), Vec3(0, 1, 0)), 0.0f);
}

}  // namespace
}  // namespace strahl
