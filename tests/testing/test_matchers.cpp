// The Catch2 matchers (testing/catch2.hpp) in this suite's own framework: a
// right matrix matches, a wrong one does not, and the description a failing
// REQUIRE_THAT prints explains the failure.
#include <qverify/testing/catch2.hpp>

using namespace qverify;

namespace {
Mat4<double> ellipsoid() { return ellipsoid_quadric<double>(Vec3<double>(1, 2, 3), Vec3<double>(1, 2, 3), Mat3<double>::Identity()); }
}  // namespace

TEST_CASE("Catch2 matchers accept the right matrices and explain the wrong ones", "[check]") {
  const Mat4<double> A = ellipsoid();
  const Vec4<double> L(4, 5, 12, 1), plane(0, 0, 1, 2);
  const ShadowResult<double> s = shadow<double>(A, L, Method::direct);
  CHECK_THAT(s.P, IsShadowConeOf(A, L));
  CHECK_THAT(s.polar_plane, IsPolarPlaneOf(A, L));
  CHECK_THAT(s.R, IsTerminatorQuadricOf(A, L));
  const Mat4<double> M = mirror_matrix<double>(plane);
  CHECK_THAT(M, IsMirrorMatrixOf(plane));
  CHECK_THAT(reflection<double>(A, M, Method::direct).B, IsMirrorImageOf(A, plane));

  auto cone = IsShadowConeOf(A, L);
  const Vec4<double> AL = A * L;
  CHECK_FALSE(cone.match(Mat4<double>(L.dot(AL) * A + AL * AL.transpose())));
  const std::string why = cone.describe();
  CHECK_THAT(why, Catch::Contains("on_generators"));
  CHECK_THAT(why, Catch::Contains("worst point"));
  CHECK_THAT(why, Catch::Contains("expected P"));
  CHECK_FALSE(IsMirrorImageOf(A, plane).match(Mat4<double>(M * A * M.transpose())));
  CHECK_FALSE(IsMirrorMatrixOf(plane).match(Mat4<double>::Identity()));
  CHECK_FALSE(IsPolarPlaneOf(A, L).match(Vec4<double>(-s.polar_plane)));

  // rationals: exact matches only
  const Mat4<Rational> Aq = exact_matrix(A);
  const Vec4<Rational> Lq = exact_matrix(L);
  CHECK_THAT(tangent_cone<Rational>(Aq, Lq), IsShadowConeOf(Aq, Lq));
  Mat4<Rational> off = tangent_cone<Rational>(Aq, Lq);
  off(2, 2) += Rational(1, 1000000000);
  CHECK_FALSE(IsShadowConeOf(Aq, Lq).match(off));
}
