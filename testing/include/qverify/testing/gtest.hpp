#pragma once
/// \file gtest.hpp
/// GoogleTest predicate formatters and gMock matchers for quadric geometry,
/// checked by qverify:
///
///   #include <qverify/testing/gtest.hpp>
///   EXPECT_PRED_FORMAT3(qverify::testing::AssertShadowCone, P, A, L);
///   EXPECT_THAT(P, qverify::testing::IsShadowConeOf(A, L));
///   EXPECT_THAT(B, qverify::testing::IsMirrorImageOf(A, plane));
///
/// Each also takes CheckOptions last (the accuracy target, samples, seed), as the
/// Catch2 matchers do: a float implementation is held to a float-sized target,
///   CheckOptions o; o.accuracy = 1e-5;
///   EXPECT_PRED_FORMAT4(qverify::testing::AssertShadowCone, P, A, L, o);
///   EXPECT_THAT(P, qverify::testing::IsShadowConeOf(A, L, o));
///
/// The same checks as the Catch2 matchers (checks.hpp): exact points on the
/// exact geometry, the geometric error against the accuracy target (rationals:
/// exactly zero). A failure explains itself: which point, how far, relative to
/// what, in which frame, and the expected matrix rounded.

#include <qverify/testing/checks.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace qverify::testing {

namespace detail {
/// A matcher's verdict, with the report for the failure message.
inline bool explained(const CheckReport& r, ::testing::MatchResultListener* listener) {
  *listener << "\n" << r.summary();
  return r.passed;
}

inline ::testing::AssertionResult verdict(const CheckReport& r, const std::string& claim) {
  if (r.passed) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << claim << "\n" << r.summary();
}
}  // namespace detail

/// EXPECT_PRED_FORMAT3(AssertShadowCone, P, A, L); EXPECT_PRED_FORMAT4(AssertShadowCone, P, A, L, options)
template <class S>
::testing::AssertionResult AssertShadowCone(const char* P_expr, const char* A_expr, const char* L_expr, const char*,
                                            const Mat4<S>& P, const Mat4<S>& A, const Vec4<S>& L, const CheckOptions& opt) {
  return detail::verdict(shadow_cone_check<S>(P, A, L, opt),
                         std::string(P_expr) + " is not the shadow cone of " + A_expr + " from " + L_expr);
}
template <class S>
::testing::AssertionResult AssertShadowCone(const char* P_expr, const char* A_expr, const char* L_expr, const Mat4<S>& P,
                                            const Mat4<S>& A, const Vec4<S>& L) {
  return AssertShadowCone<S>(P_expr, A_expr, L_expr, "", P, A, L, CheckOptions{});
}

/// EXPECT_PRED_FORMAT3(AssertPolarPlane, pi, A, L), or FORMAT4 with options
template <class S>
::testing::AssertionResult AssertPolarPlane(const char* pi_expr, const char* A_expr, const char* L_expr, const char*,
                                            const Vec4<S>& pi, const Mat4<S>& A, const Vec4<S>& L, const CheckOptions& opt) {
  return detail::verdict(polar_plane_check<S>(pi, A, L, opt),
                         std::string(pi_expr) + " is not the polar plane of " + L_expr + " with respect to " + A_expr);
}
template <class S>
::testing::AssertionResult AssertPolarPlane(const char* pi_expr, const char* A_expr, const char* L_expr, const Vec4<S>& pi,
                                            const Mat4<S>& A, const Vec4<S>& L) {
  return AssertPolarPlane<S>(pi_expr, A_expr, L_expr, "", pi, A, L, CheckOptions{});
}

/// EXPECT_PRED_FORMAT3(AssertTerminatorQuadric, R, A, L), or FORMAT4 with options
template <class S>
::testing::AssertionResult AssertTerminatorQuadric(const char* R_expr, const char* A_expr, const char* L_expr, const char*,
                                                   const Mat4<S>& R, const Mat4<S>& A, const Vec4<S>& L,
                                                   const CheckOptions& opt) {
  return detail::verdict(terminator_quadric_check<S>(R, A, L, opt),
                         std::string(R_expr) + " is not the terminator quadric R of " + A_expr + " from " + L_expr);
}
template <class S>
::testing::AssertionResult AssertTerminatorQuadric(const char* R_expr, const char* A_expr, const char* L_expr,
                                                   const Mat4<S>& R, const Mat4<S>& A, const Vec4<S>& L) {
  return AssertTerminatorQuadric<S>(R_expr, A_expr, L_expr, "", R, A, L, CheckOptions{});
}

/// EXPECT_PRED_FORMAT3(AssertMirrorImage, B, A, plane), or FORMAT4 with options
template <class S>
::testing::AssertionResult AssertMirrorImage(const char* B_expr, const char* A_expr, const char* plane_expr, const char*,
                                             const Mat4<S>& B, const Mat4<S>& A, const Vec4<S>& plane,
                                             const CheckOptions& opt) {
  return detail::verdict(mirror_image_check<S>(B, A, plane, opt),
                         std::string(B_expr) + " is not the mirror image of " + A_expr + " in " + plane_expr);
}
template <class S>
::testing::AssertionResult AssertMirrorImage(const char* B_expr, const char* A_expr, const char* plane_expr,
                                             const Mat4<S>& B, const Mat4<S>& A, const Vec4<S>& plane) {
  return AssertMirrorImage<S>(B_expr, A_expr, plane_expr, "", B, A, plane, CheckOptions{});
}

/// EXPECT_PRED_FORMAT2(AssertMirrorMatrix, M, plane), or FORMAT3 with options
template <class S>
::testing::AssertionResult AssertMirrorMatrix(const char* M_expr, const char* plane_expr, const char*, const Mat4<S>& M,
                                              const Vec4<S>& plane, const CheckOptions& opt) {
  return detail::verdict(mirror_matrix_check<S>(M, plane, opt),
                         std::string(M_expr) + " is not the reflection in " + plane_expr);
}
template <class S>
::testing::AssertionResult AssertMirrorMatrix(const char* M_expr, const char* plane_expr, const Mat4<S>& M,
                                              const Vec4<S>& plane) {
  return AssertMirrorMatrix<S>(M_expr, plane_expr, "", M, plane, CheckOptions{});
}

/// gMock matchers: EXPECT_THAT(P, IsShadowConeOf(A, L)). The scalar type is
/// the candidate's; A and L are taken in it.
MATCHER_P2(IsShadowConeOf, A, L, "is the shadow cone of the quadric from the light (qverify)") {
  return detail::explained(shadow_cone_check(arg, A, L), result_listener);
}

MATCHER_P2(IsPolarPlaneOf, A, L, "is the polar plane of the light with respect to the quadric (qverify)") {
  return detail::explained(polar_plane_check(arg, A, L), result_listener);
}

MATCHER_P2(IsTerminatorQuadricOf, A, L, "is the terminator quadric R of the quadric from the light (qverify)") {
  return detail::explained(terminator_quadric_check(arg, A, L), result_listener);
}

MATCHER_P2(IsMirrorImageOf, A, plane, "is the mirror image of the quadric in the plane (qverify)") {
  return detail::explained(mirror_image_check(arg, A, plane), result_listener);
}

MATCHER_P(IsMirrorMatrixOf, plane, "is the reflection in the plane (qverify)") {
  return detail::explained(mirror_matrix_check(arg, plane), result_listener);
}

/// The same with CheckOptions last: EXPECT_THAT(P, IsShadowConeOf(A, L, options)).
MATCHER_P3(IsShadowConeOf, A, L, opt, "is the shadow cone of the quadric from the light (qverify)") {
  return detail::explained(shadow_cone_check(arg, A, L, opt), result_listener);
}

MATCHER_P3(IsPolarPlaneOf, A, L, opt, "is the polar plane of the light with respect to the quadric (qverify)") {
  return detail::explained(polar_plane_check(arg, A, L, opt), result_listener);
}

MATCHER_P3(IsTerminatorQuadricOf, A, L, opt, "is the terminator quadric R of the quadric from the light (qverify)") {
  return detail::explained(terminator_quadric_check(arg, A, L, opt), result_listener);
}

MATCHER_P3(IsMirrorImageOf, A, plane, opt, "is the mirror image of the quadric in the plane (qverify)") {
  return detail::explained(mirror_image_check(arg, A, plane, opt), result_listener);
}

MATCHER_P2(IsMirrorMatrixOf, plane, opt, "is the reflection in the plane (qverify)") {
  return detail::explained(mirror_matrix_check(arg, plane, opt), result_listener);
}

}  // namespace qverify::testing
