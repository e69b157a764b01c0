#pragma once
/// \file mirror.hpp
/// Mirror image of a quadric in a plane mirror, equations (7)-(11).
///
/// The mirror is the plane n.x + d = 0, given as (a, b, c, d) with any
/// non-zero normal n = (a, b, c) (the paper's (7) writes the constant as 1 and
/// its (9) assumes |n| = 1; neither is needed here). The reflection is
///   y = x - 2 (n.x + d) n / (n.n),
/// rational in n and d: no square root, exact for exact types.

#include <qverify/core/method.hpp>
#include <qverify/core/predicates.hpp>
#include <qverify/core/quadric.hpp>

namespace qverify {

/// The mirror matrix is a rank-one update of the identity, M = E - 2 h w^T,
/// with w = (n, d) the mirror plane and h = (n, 0) / (n.n) (eq. (9)): this
/// returns h, the one division of the reflection. (The 2 is applied as h + h,
/// exact in binary floating point and in intervals; in double 2 h is bitwise
/// the (2 / (n.n)) n of the textbook form.) Precondition: n != 0.
template <class S> Vec4<S> mirror_half_direction(const Vec4<S>& plane) {
  const Vec3<S> n = plane.template head<3>();
  const S k = S(1) / ordered_dot<S, 3>(n, n);
  return Vec4<S>(k * n(0), k * n(1), k * n(2), S(0));
}

/// The entries of rows 1-3 of M = E - 2 h w^T, M_ij = E_ij - (h_i + h_i) w_j
/// (i < 3), from h = mirror_half_direction(w), as a function of (i, j):
/// batches store the twelve entries of packs straight from it (as
/// tangent_cone_entries in shadow.hpp). It refers to h and the plane: use it
/// while they live.
template <class S> [[nodiscard]] auto mirror_matrix_entries(const Vec4<S>& h, const Vec4<S>& plane) {
  return [&h, &plane](int i, int j) { return S((i == j ? S(1) : S(0)) - (h(i) + h(i)) * plane(j)); };
}

/// M = E - 2 h w^T from h = mirror_half_direction(w), entry by entry.
template <class S> Mat4<S> mirror_matrix_from(const Vec4<S>& h, const Vec4<S>& plane) {
  const auto entry = mirror_matrix_entries<S>(h, plane);
  Mat4<S> M = Mat4<S>::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) M(i, j) = entry(i, j);
  return M;
}

/// Eq. (9), the mirror matrix, corrected for a non-unit normal:
///   M = [[I - 2 n n^T / (n.n), -2 d n / (n.n)], [0 0 0 1]] = E - u w^T.
/// M M = I (eq. (11)'s M = M^{-1}) and M fixes its plane pointwise.
/// Precondition: n != 0.
template <class S> Mat4<S> mirror_matrix(const Vec4<S>& plane) {
  return mirror_matrix_from<S>(mirror_half_direction<S>(plane), plane);
}

/// (n.n) times the mirror matrix, division-free (for exact integer types):
///   [[(n.n) I - 2 n n^T, -2 d n], [0 0 0 n.n]].
/// As a projective map it is the reflection itself; B from it carries the
/// positive factor (n.n)^2.
template <class S> Mat4<S> scaled_mirror_matrix(const Vec4<S>& plane) {
  // Entry by entry: for a wide integer type every Eigen temporary (nn I, 2 n n^T) costs
  // multiplications by zero and copies (the exact reflection rows of qverify bench).
  const Vec3<S> n = plane.template head<3>();
  const Vec3<S> n2(n(0) + n(0), n(1) + n(1), n(2) + n(2));  // 2 n, without a product
  const S nn = ordered_dot<S, 3>(n, n);
  Mat4<S> M;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) M(i, j) = i == j ? S(nn - n2(i) * n(j)) : S(-(n2(i) * n(j)));
    M(i, 3) = -(n2(i) * plane(3));
    M(3, i) = S(0);
  }
  M(3, 3) = nn;
  return M;
}

/// Eq. (11), direct: B = M^T A M (using M = M^{-1}). A point x lies on A
/// exactly when its mirror image M x lies on B.
template <class S> Mat4<S> mirror_image(const Mat4<S>& A, const Mat4<S>& M) {
  return congruence<S>(A, M);
}

/// Eq. (11), the paper's first form: B = (M^{-1})^T A M^{-1} with M^{-1}
/// computed as an inverse (not assumed equal to M).
template <class S> Mat4<S> mirror_image_paper(const Mat4<S>& A, const Mat4<S>& M) {
  return congruence<S>(A, Mat4<S>(M.inverse()));
}

/// Eq. (11) without forming M^T A M. The mirror matrix is a rank-one update
/// of the identity, M = E - u w^T with w = (n, d) the mirror plane and
/// u = 2 h, h = (n, 0) / (n.n); hence, with a = A u,
///   B = M^T A M = A - w a^T - a w^T + (u^T a) w w^T = A - w c^T - c w^T,
///   c = a - (h^T a) w          (since u^T a = 2 h^T a),
/// and as u_4 = h_4 = 0 only the first three columns of A enter a:
/// 12 + 3 + 4 + 20 = 39 products (two 4x4 products take 128), and the same B
/// exactly in exact arithmetic (tests check the identity).
/// `h` = mirror_half_direction(plane). mirror_image_entries gives B_ij as a
/// function of (i, j) (batches store the ten entries of packs straight from
/// it, as tangent_cone_entries in shadow.hpp); it refers to A and the plane:
/// use it while they live.
template <class S> [[nodiscard]] auto mirror_image_entries(const Mat4<S>& A, const Vec4<S>& h, const Vec4<S>& plane) {
  const Vec3<S> u(h(0) + h(0), h(1) + h(1), h(2) + h(2));
  Vec4<S> a;
  for (int i = 0; i < 4; ++i) a(i) = ordered_dot<S, 3>(A.row(i).template head<3>().transpose(), u);
  const S beta = ordered_dot<S, 3>(h.template head<3>(), a.template head<3>());  // u^T a / 2
  Vec4<S> c;
  for (int i = 0; i < 4; ++i) c(i) = a(i) - beta * plane(i);
  return [&A, &plane, c](int i, int j) { return S(A(i, j) - (plane(i) * c(j) + c(i) * plane(j))); };
}
/// B = A - w c^T - c w^T, the mirror image from h (the matrix of mirror_image_entries).
template <class S> Mat4<S> mirror_image_from(const Mat4<S>& A, const Vec4<S>& h, const Vec4<S>& plane) {
  return symmetric_from<S>(mirror_image_entries<S>(A, h, plane));
}

template <class S> Mat4<S> mirror_image_of_plane(const Mat4<S>& A, const Vec4<S>& plane) {
  return mirror_image_from<S>(A, mirror_half_direction<S>(plane), plane);
}

template <class S> struct ReflectionResult {
  Mat4<S> B;
  bool degenerate = false;  ///< rank A <= 2 (status degenerate-quadric)
  bool undecided = false;   ///< the floating filter could not decide rank A <= 2 (exact/statuses.hpp settles it)
  const char* status() const { return degenerate ? "degenerate-quadric" : undecided ? "undecided" : "ok"; }
};

/// The status predicate of a reflection: degenerate-quadric (rank A <= 2),
/// exactly for exact types, through the certified filter otherwise.
template <class S> Truth reflection_degenerate(const Mat4<S>& A) {
  using P = PredicateScalar<S>;
  return degenerate_quadric<P>(to_predicate<P>(A));
}

template <class S> void set_reflection_status(ReflectionResult<S>& r, Truth degenerate) {
  r.degenerate = degenerate == Truth::yes;
  r.undecided = degenerate == Truth::unknown;
}

/// Mirror image of A in the mirror with matrix M, by either route.
template <class S> ReflectionResult<S> reflection(const Mat4<S>& A, const Mat4<S>& M, Method method) {
  ReflectionResult<S> r;
  set_reflection_status(r, reflection_degenerate<S>(A));
  r.B = method == Method::paper ? mirror_image_paper<S>(A, M) : mirror_image<S>(A, M);
  return r;
}

/// Mirror image of A in the mirror `plane`: direct, by the rank-one form
/// (mirror_image_of_plane); paper, (M^-1)^T A M^-1 with M from (9).
template <class S> ReflectionResult<S> reflection_in_plane(const Mat4<S>& A, const Vec4<S>& plane, Method method) {
  ReflectionResult<S> r;
  set_reflection_status(r, reflection_degenerate<S>(A));
  r.B = method == Method::paper ? mirror_image_paper<S>(A, mirror_matrix<S>(plane)) : mirror_image_of_plane<S>(A, plane);
  return r;
}

}  // namespace qverify
