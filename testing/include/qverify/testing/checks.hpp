#pragma once
/// \file checks.hpp
/// What each test-framework matcher asks (catch2.hpp, gtest.hpp), written once:
/// one candidate matrix against the exact inputs, through check_shadow /
/// check_reflection (verify/check.hpp), with `qverify verify`'s semantics:
/// a floating matrix passes when its geometric error (largest first-order
/// distance of exact sample points, relative to the object size) is at most
/// the accuracy target, and it is the object it claims to be (a cone from L,
/// the right sign); a rational matrix passes only when every residual is
/// exactly zero. A matcher's verdict is pass or fail: where the geometry has no
/// real point to sample (a lamp inside an ellipsoid), which `verify` skips, the
/// matrix is judged against the exact one up to a factor
/// (CheckOptions::judge_without_points, set here whatever the options given).

#include <qverify/verify/check.hpp>

#include <string>

namespace qverify::testing {

/// The options a matcher checks with: the caller's, judged without points where there are none.
inline CheckOptions matcher_options(CheckOptions opt) {
  opt.judge_without_points = true;
  return opt;
}

/// P is the shadow cone of A from the light L (eq. 2): (L^T A L) A - (A L)(A L)^T up to a positive factor.
template <class S>
CheckReport shadow_cone_check(const Mat4<S>& P, const Mat4<S>& A, const Vec4<S>& L, const CheckOptions& opt = {}) {
  ShadowCandidate<S> c;
  c.P = P;
  return check_shadow<S>(A, L, c, matcher_options(opt));
}

/// pi is the polar plane A L of the light (the plane of the terminator), up to a positive factor.
template <class S>
CheckReport polar_plane_check(const Vec4<S>& pi, const Mat4<S>& A, const Vec4<S>& L, const CheckOptions& opt = {}) {
  ShadowCandidate<S> c;
  c.polar_plane = pi;
  return check_shadow<S>(A, L, c, matcher_options(opt));
}

/// R is the paper's second quadric (eq. 6): the polar plane and the plane its frame sends to infinity.
template <class S>
CheckReport terminator_quadric_check(const Mat4<S>& R, const Mat4<S>& A, const Vec4<S>& L, const CheckOptions& opt = {}) {
  ShadowCandidate<S> c;
  c.R = R;
  return check_shadow<S>(A, L, c, matcher_options(opt));
}

/// B is the mirror image M^T A M of A in the plane a x + b y + c z + d = 0 (eq. 11), up to a positive factor.
template <class S>
CheckReport mirror_image_check(const Mat4<S>& B, const Mat4<S>& A, const Vec4<S>& plane, const CheckOptions& opt = {}) {
  ReflectionCandidate<S> c;
  c.B = B;
  return check_reflection<S>(A, plane, c, matcher_options(opt));
}

/// M is the reflection in the plane (eq. 7), entrywise within the accuracy
/// target relative to max(1, |M|_max) (exactly, for rationals).
template <class S>
CheckReport mirror_matrix_check(const Mat4<S>& M, const Vec4<S>& plane, const CheckOptions& opt = {}) {
  ReflectionCandidate<S> c;
  c.M = M;
  // M needs no sample points; a unit sphere stands in for the quadric the check asks for.
  return check_reflection<S>(sphere_quadric<S>(Vec3<S>(S(0), S(0), S(0)), S(1)), plane, c, matcher_options(opt));
}

}  // namespace qverify::testing
