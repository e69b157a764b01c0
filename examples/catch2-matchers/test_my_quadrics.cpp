// A renderer's Catch2 tests of its own shadow and mirror code, checked by qverify.
#define CATCH_CONFIG_MAIN
#include <qverify/testing/catch2.hpp>

#include "my_quadrics.hpp"

using qverify::IsMirrorImageOf;
using qverify::IsShadowConeOf;

namespace {
// An ellipsoid (semi-axes 1, 2, 3) centred at (1, 2, 3): x^T A x = 0.
Eigen::Matrix4d ellipsoid() {
  return qverify::ellipsoid_quadric<double>(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 3), Eigen::Matrix3d::Identity());
}
const Eigen::Vector4d lamp(4, 5, 12, 1);          // a point light (x, y, z, 1)
const Eigen::Vector4d sun(-1, -2, -10, 0);        // a parallel light (direction, 0)
const Eigen::Vector4d floor_mirror(0, 0, 1, 2);   // the mirror z = -2
}  // namespace

TEST_CASE("my shadow cone is the shadow cone, for a lamp and the sun") {
  REQUIRE_THAT(mine::shadow_cone(ellipsoid(), lamp), IsShadowConeOf(ellipsoid(), lamp));
  REQUIRE_THAT(mine::shadow_cone(ellipsoid(), sun), IsShadowConeOf(ellipsoid(), sun));
}

TEST_CASE("my mirror image is the mirror image") {
  REQUIRE_THAT(mine::mirror_image(ellipsoid(), floor_mirror), IsMirrorImageOf(ellipsoid(), floor_mirror));
}

// The slips must be caught: these tests are expected to fail ([!shouldfail]).
TEST_CASE("the slipped shadow cone is caught", "[!shouldfail]") {
  REQUIRE_THAT(mine::shadow_cone_with_slip(ellipsoid(), lamp), IsShadowConeOf(ellipsoid(), lamp));
}

TEST_CASE("the slipped mirror image is caught", "[!shouldfail]") {
  REQUIRE_THAT(mine::mirror_image_with_slip(ellipsoid(), floor_mirror), IsMirrorImageOf(ellipsoid(), floor_mirror));
}
