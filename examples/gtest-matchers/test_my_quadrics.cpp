// A renderer's GoogleTest tests of its own shadow and mirror code, checked by qverify.
#include <qverify/testing/gtest.hpp>

#include <gtest/gtest-spi.h>

#include "my_quadrics.hpp"

using qverify::testing::AssertShadowCone;
using qverify::testing::IsMirrorImageOf;
using qverify::testing::IsShadowConeOf;

namespace {
// An ellipsoid (semi-axes 1, 2, 3) centred at (1, 2, 3): x^T A x = 0.
Eigen::Matrix4d ellipsoid() {
  return qverify::ellipsoid_quadric<double>(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 3), Eigen::Matrix3d::Identity());
}
const Eigen::Vector4d lamp(4, 5, 12, 1);          // a point light (x, y, z, 1)
const Eigen::Vector4d sun(-1, -2, -10, 0);        // a parallel light (direction, 0)
const Eigen::Vector4d floor_mirror(0, 0, 1, 2);   // the mirror z = -2
}  // namespace

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
