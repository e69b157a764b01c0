// A renderer's GoogleTest tests of its own shadow and mirror code, checked by qverify.
#include <qverify/testing/gtest.hpp>

#include <gtest/gtest-spi.h>

#include "fixtures.hpp"
#include "my_quadrics.hpp"  // the code under test

using qverify::testing::AssertShadowCone;
using qverify::testing::IsMirrorImageOf;
using qverify::testing::IsShadowConeOf;

using namespace fixtures;

TEST(MyShadows, ConeFromALampAndTheSun) {
  const Eigen::Matrix4d A = ellipsoid();
  EXPECT_THAT(mine::shadow_cone(A, lamp), IsShadowConeOf(A, lamp));
  EXPECT_PRED_FORMAT3(AssertShadowCone, mine::shadow_cone(A, sun), A, sun);
}

TEST(MyMirrors, MirrorImage) {
  const Eigen::Matrix4d A = ellipsoid();
  EXPECT_THAT(mine::mirror_image(A, floor_mirror), IsMirrorImageOf(A, floor_mirror));
}

// The slips must be caught: each assertion is expected to fail, with qverify's explanation.
TEST(MySlips, AreCaught) {
  const Eigen::Matrix4d A = ellipsoid();
  EXPECT_NONFATAL_FAILURE(EXPECT_THAT(mine::shadow_cone_with_slip(A, lamp), IsShadowConeOf(A, lamp)),
                          "on_generators");
  EXPECT_NONFATAL_FAILURE(EXPECT_PRED_FORMAT3(AssertShadowCone, mine::shadow_cone_with_slip(A, lamp), A, lamp),
                          "is not the shadow cone");
  EXPECT_NONFATAL_FAILURE(EXPECT_THAT(mine::mirror_image_with_slip(A, floor_mirror), IsMirrorImageOf(A, floor_mirror)),
                          "worst point");
}
