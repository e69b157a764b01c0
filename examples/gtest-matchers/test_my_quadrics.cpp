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

// A lamp inside the ellipsoid: no real terminator point to sample. The matchers still give a
// verdict, judging the cone against the exact one up to a factor: the right one passes, the slip fails.
TEST(MyShadows, LampInside) {
  const Eigen::Matrix4d A = ellipsoid();
  const Eigen::Vector4d inside(1, 2, 3, 1);  // the centre
  EXPECT_THAT(mine::shadow_cone(A, inside), IsShadowConeOf(A, inside));
  EXPECT_NONFATAL_FAILURE(EXPECT_THAT(mine::shadow_cone_with_slip(A, inside), IsShadowConeOf(A, inside)),
                          "judged as matrices");
}

// Options last, as for the Catch2 matchers: the accuracy target. A float renderer's cone is about
// float's epsilon off: it fails the default target 1e-9 and passes a float-sized one.
TEST(MyShadows, AccuracyTarget) {
  const Eigen::Matrix4f A = ellipsoid().cast<float>();
  const Eigen::Vector4f L(4.1f, 5.3f, 12.7f, 1);  // (the fixtures' integers would make float exact)
  const Eigen::Vector4f AL = A * L;
  const Eigen::Matrix4f P = L.dot(AL) * A - AL * AL.transpose();  // the same formula, in float
  EXPECT_NONFATAL_FAILURE(EXPECT_THAT(P, IsShadowConeOf(A, L)), "accuracy target 1e-09");
  qverify::CheckOptions loose;
  loose.accuracy = 1e-5;
  EXPECT_THAT(P, IsShadowConeOf(A, L, loose));
  EXPECT_PRED_FORMAT4(AssertShadowCone, P, A, L, loose);
  // every matcher and predicate formatter takes the options (here the right double results)
  const Eigen::Matrix4d Ad = ellipsoid();
  const Eigen::Vector4d pi = Ad * lamp;
  const Eigen::Vector4d h(0, 0, lamp(3), -lamp(2));  // R's second plane z = l_z
  const Eigen::Matrix4d R = pi * h.transpose() + h * pi.transpose();
  const Eigen::Matrix4d M = mine::mirror(floor_mirror), B = mine::mirror_image(Ad, floor_mirror);
  EXPECT_THAT(pi, qverify::testing::IsPolarPlaneOf(Ad, lamp, loose));
  EXPECT_THAT(R, qverify::testing::IsTerminatorQuadricOf(Ad, lamp, loose));
  EXPECT_THAT(B, IsMirrorImageOf(Ad, floor_mirror, loose));
  EXPECT_THAT(M, qverify::testing::IsMirrorMatrixOf(floor_mirror, loose));
  EXPECT_PRED_FORMAT4(qverify::testing::AssertPolarPlane, pi, Ad, lamp, loose);
  EXPECT_PRED_FORMAT4(qverify::testing::AssertTerminatorQuadric, R, Ad, lamp, loose);
  EXPECT_PRED_FORMAT4(qverify::testing::AssertMirrorImage, B, Ad, floor_mirror, loose);
  EXPECT_PRED_FORMAT3(qverify::testing::AssertMirrorMatrix, M, floor_mirror, loose);
  EXPECT_PRED_FORMAT3(qverify::testing::AssertPolarPlane, pi, Ad, lamp);
  EXPECT_PRED_FORMAT3(qverify::testing::AssertTerminatorQuadric, R, Ad, lamp);
  EXPECT_PRED_FORMAT3(qverify::testing::AssertMirrorImage, B, Ad, floor_mirror);
  EXPECT_PRED_FORMAT2(qverify::testing::AssertMirrorMatrix, M, floor_mirror);
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
