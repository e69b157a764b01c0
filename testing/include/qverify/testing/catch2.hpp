#pragma once
/// \file catch2.hpp
/// Catch2 (v2) matchers for quadric geometry, checked by qverify:
///
///   #include <qverify/testing/catch2.hpp>
///   REQUIRE_THAT(P, qverify::IsShadowConeOf(A, L));
///   CHECK_THAT(B, qverify::IsMirrorImageOf(A, plane));
///
/// Each matcher samples exact points on the exact geometry of (A, L) or
/// (A, plane) and measures the candidate there (checks.hpp). On failure the
/// message says which point, how far, relative to what object size, in which
/// frame, and prints the exact expected matrix rounded to double. The matrices'
/// scalar type is any of qverify's (float, double, long double, float128,
/// mpfr, interval, Rational); rationals are held to exact zero residuals.

#include <qverify/testing/checks.hpp>

#include <catch2/catch.hpp>

#include <functional>
#include <string>

namespace qverify {
namespace testing {

/// One matcher class for every check: the candidate's type T and the check to run.
template <class T> class QuadricMatcher : public Catch::MatcherBase<T> {
 public:
  QuadricMatcher(std::string what, std::function<CheckReport(const T&)> check)
      : what_(std::move(what)), check_(std::move(check)) {}
  bool match(const T& candidate) const override {
    const CheckReport r = check_(candidate);
    report_ = r.summary();
    return r.passed;
  }
  /// Catch asks for the description after match(): it carries the report.
  std::string describe() const override { return what_ + (report_.empty() ? "" : "\n" + report_); }

 private:
  std::string what_;
  std::function<CheckReport(const T&)> check_;
  mutable std::string report_;
};

}  // namespace testing

/// REQUIRE_THAT(P, IsShadowConeOf(A, L)): P is the shadow cone of A from L.
template <class S>
testing::QuadricMatcher<Mat4<S>> IsShadowConeOf(const Mat4<S>& A, const Vec4<S>& L, const CheckOptions& opt = {}) {
  return {"is the shadow cone of A from L (qverify)",
          [=](const Mat4<S>& P) { return testing::shadow_cone_check<S>(P, A, L, opt); }};
}

/// REQUIRE_THAT(pi, IsPolarPlaneOf(A, L)): pi is the plane of the terminator, oriented as A L.
template <class S>
testing::QuadricMatcher<Vec4<S>> IsPolarPlaneOf(const Mat4<S>& A, const Vec4<S>& L, const CheckOptions& opt = {}) {
  return {"is the polar plane of L with respect to A (qverify)",
          [=](const Vec4<S>& pi) { return testing::polar_plane_check<S>(pi, A, L, opt); }};
}

/// REQUIRE_THAT(R, IsTerminatorQuadricOf(A, L)): R is the paper's R (eq. 6).
template <class S>
testing::QuadricMatcher<Mat4<S>> IsTerminatorQuadricOf(const Mat4<S>& A, const Vec4<S>& L, const CheckOptions& opt = {}) {
  return {"is the terminator quadric R of A from L (qverify)",
          [=](const Mat4<S>& R) { return testing::terminator_quadric_check<S>(R, A, L, opt); }};
}

/// REQUIRE_THAT(B, IsMirrorImageOf(A, plane)): B is A reflected in the plane.
template <class S>
testing::QuadricMatcher<Mat4<S>> IsMirrorImageOf(const Mat4<S>& A, const Vec4<S>& plane, const CheckOptions& opt = {}) {
  return {"is the mirror image of A in the plane (qverify)",
          [=](const Mat4<S>& B) { return testing::mirror_image_check<S>(B, A, plane, opt); }};
}

/// REQUIRE_THAT(M, IsMirrorMatrixOf(plane)): M is the reflection in the plane.
template <class S>
testing::QuadricMatcher<Mat4<S>> IsMirrorMatrixOf(const Vec4<S>& plane, const CheckOptions& opt = {}) {
  return {"is the reflection in the plane (qverify)",
          [=](const Mat4<S>& M) { return testing::mirror_matrix_check<S>(M, plane, opt); }};
}

}  // namespace qverify
