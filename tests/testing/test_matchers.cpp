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

TEST_CASE("matchers give a verdict where the geometry has no real point: judged as matrices, as verify skips it",
          "[check]") {
  // A lamp inside a sphere, and an imaginary sphere in a mirror: verify skips such items (neither pass
  // nor fail); a matcher must pass a right result and fail a wrong one (audit 42d: every matcher failed
  // the right one as "SKIPPED").
  const Mat4<double> A = sphere_quadric<double>(Vec3<double>(0, 0, 0), 2);
  const Vec4<double> inside(0, 0, 1, 1), plane(0, 0, 1, 2);
  const Mat4<double> P = tangent_cone<double>(A, inside);
  ShadowCandidate<double> c;
  c.P = P;
  CHECK(check_shadow<double>(A, inside, c).skipped);  // verify's way
  CHECK_THAT(P, IsShadowConeOf(A, inside));
  Mat4<double> off = P;
  off(0, 3) = off(3, 0) = 1e-6 * P.cwiseAbs().maxCoeff();
  auto cone = IsShadowConeOf(A, inside);
  CHECK_FALSE(cone.match(off));
  CHECK_THAT(cone.describe(), Catch::Contains("judged as matrices"));
  CHECK_FALSE(IsShadowConeOf(A, inside).match(Mat4<double>(-P)));  // the sign counts

  // every matcher, and the exact proof mode: a rational P exactly right passes, one off by 2^-60 fails
  CHECK_THAT(Vec4<double>(A * inside), IsPolarPlaneOf(A, inside));
  CHECK_FALSE(IsPolarPlaneOf(A, inside).match(Vec4<double>(-(A * inside))));
  const ShadowResult<double> s = shadow<double>(A, inside, Method::direct);
  CHECK_THAT(s.R, IsTerminatorQuadricOf(A, inside));
  const Mat4<Rational> Aq = exact_matrix(A);
  const Vec4<Rational> Lq = exact_matrix(inside);
  const Mat4<Rational> Pq = tangent_cone<Rational>(Aq, Lq);
  CHECK_THAT(Pq, IsShadowConeOf(Aq, Lq));
  Mat4<Rational> Pq_off = Pq;
  Pq_off(0, 1) = Pq_off(1, 0) = Rational(1, 1152921504606846976LL);  // 2^-60
  CHECK_FALSE(IsShadowConeOf(Aq, Lq).match(Pq_off));

  Mat4<double> imaginary = Mat4<double>::Identity();  // x^2 + y^2 + z^2 + 1 = 0
  const Mat4<double> M = mirror_matrix<double>(plane);
  const Mat4<double> B = reflection<double>(imaginary, M, Method::direct).B;
  ReflectionCandidate<double> r;
  r.B = B;
  CHECK(check_reflection<double>(imaginary, plane, r).skipped);
  CHECK_THAT(B, IsMirrorImageOf(imaginary, plane));
  CHECK_FALSE(IsMirrorImageOf(imaginary, plane).match(imaginary));  // (not through the origin: B differs)
  // M alone on a quadric without real points: judged without points, a verdict either way
  CheckOptions judge;
  judge.judge_without_points = true;
  ReflectionCandidate<double> m;
  m.M = M;
  CHECK(check_reflection<double>(imaginary, plane, m).skipped);
  const CheckReport right = check_reflection<double>(imaginary, plane, m, judge);
  CHECK(right.passed);
  CHECK_FALSE(right.skipped);
  (*m.M)(2, 3) += 0.5;
  const CheckReport wrong = check_reflection<double>(imaginary, plane, m, judge);
  CHECK_FALSE(wrong.passed);
  CHECK_FALSE(wrong.skipped);
  CHECK_THAT(wrong.summary(), Catch::Contains("expected M"));
}

TEST_CASE("a wrong M is explained by M's own error and the expected M, not by the stand-in quadric's B", "[check]") {
  const Vec4<double> plane(0, 0, 1, 0);
  Mat4<double> M = mirror_matrix<double>(plane);
  M(2, 3) += 0.5;
  auto m = IsMirrorMatrixOf(plane);
  CHECK_FALSE(m.match(M));
  const std::string why = m.describe();
  CHECK_THAT(why, Catch::Contains("expected M"));
  CHECK_THAT(why, Catch::Contains("M's largest entry off the reflection: 0.5"));
  CHECK_THAT(why, !Catch::Contains("expected B"));
}
