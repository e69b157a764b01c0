// A renderer's Catch2 tests of its own shadow and mirror code, checked by qverify.
#define CATCH_CONFIG_MAIN
#include <qverify/testing/catch2.hpp>

#include "fixtures.hpp"
#include "my_quadrics.hpp"  // the code under test

using qverify::IsMirrorImageOf;
using qverify::IsShadowConeOf;

using namespace fixtures;

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
