#pragma once
/// \file quadric.hpp
/// Quadrics as symmetric 4x4 matrices, equation (1) of the paper:
///   x^T A x = 0,  x = (x, y, z, 1)  (homogeneous).
/// Every shape of the scene format is built *without square roots*, from
/// |axis|^2, r^2 and t^2 only, so an exact scalar type stays exact.
/// Convention of the scene format: the form is negative inside.

#include <qverify/core/scalar.hpp>

namespace qverify {

/// Quadric with a given 3x3 quadratic part K centred at c:
///   (x - c)^T K (x - c) + k0 = 0
///   A = [[K, -K c], [-(K c)^T, c^T K c + k0]].
template <class S>
Mat4<S> centred_quadric(const Mat3<S>& K, const Vec3<S>& c, const S& k0) {
  Mat4<S> A;
  const Vec3<S> Kc = K * c;
  A.template topLeftCorner<3, 3>() = K;
  A.template topRightCorner<3, 1>() = -Kc;
  A.template bottomLeftCorner<1, 3>() = -Kc.transpose();
  A(3, 3) = c.dot(Kc) + k0;
  return A;
}

/// Quadric of the general polynomial
///   xx x^2 + yy y^2 + zz z^2 + xy xy + xz xz + yz yz + x x + y y + z z + c = 0.
/// Off-diagonal matrix entries are half the mixed coefficients.
template <class S>
Mat4<S> quadric_from_coefficients(const S& xx, const S& yy, const S& zz, const S& xy, const S& xz,
                                  const S& yz, const S& x, const S& y, const S& z, const S& c) {
  const S h = S(1) / S(2);
  Mat4<S> A;
  A << xx, h * xy, h * xz, h * x,  //
      h * xy, yy, h * yz, h * y,   //
      h * xz, h * yz, zz, h * z,   //
      h * x, h * y, h * z, c;
  return A;
}

/// Sphere |x - center|^2 - r^2 = 0.
template <class S> Mat4<S> sphere_quadric(const Vec3<S>& center, const S& r) {
  return centred_quadric<S>(Mat3<S>::Identity(), center, S(-(r * r)));
}

/// Adjugate (classical adjoint) of a 3x3 matrix: adj(G) G = det(G) I.
template <class S> Mat3<S> adjugate3(const Mat3<S>& G) {
  Mat3<S> adj;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      adj(i, j) = G(r0, c0) * G(r1, c1) - G(r0, c1) * G(r1, c0);
    }
  return adj;
}

/// Ellipsoid: the image of the unit sphere under x = center + G u with
/// G = axes * diag(radii) (axes need not be orthonormal).
/// |G^{-1}(x - c)|^2 = 1, multiplied by det(G)^2 > 0 to stay division-free:
///   (x - c)^T adj(G)^T adj(G) (x - c) - det(G)^2 = 0.
/// The same formula for a singular G (a zero radius, singular axes; legal in a
/// scene): adj(G) of rank 1 gives the plane of the flattened ellipsoid counted
/// twice (rank 1), rank 0 the zero matrix: degenerate quadrics, not errors.
template <class S>
Mat4<S> ellipsoid_quadric(const Vec3<S>& center, const Vec3<S>& radii, const Mat3<S>& axes) {
  const Mat3<S> G = axes * radii.asDiagonal();
  const Mat3<S> adj = adjugate3<S>(G);
  const S det = (G.row(0)).dot(adj.col(0));
  return centred_quadric<S>(adj.transpose() * adj, center, S(-(det * det)));
}

/// Infinite circular cylinder through `point` along `axis` (any non-zero length):
///   |a|^2 |u|^2 - (a.u)^2 - r^2 |a|^2 = 0,  u = x - point
/// (the squared distance to the axis, times |a|^2).
template <class S> Mat4<S> cylinder_quadric(const Vec3<S>& point, const Vec3<S>& axis, const S& r) {
  const S aa = axis.squaredNorm();
  const Mat3<S> K = aa * Mat3<S>::Identity() - axis * axis.transpose();
  return centred_quadric<S>(K, point, S(-(r * r * aa)));
}

/// Infinite double cone with apex, axis and t = tan(half angle):
///   |a|^2 |u|^2 - (1 + t^2) (a.u)^2 = 0,  u = x - apex
/// (|u_perp|^2 = t^2 |u_par|^2, times |a|^2).
template <class S> Mat4<S> cone_quadric(const Vec3<S>& apex, const Vec3<S>& axis, const S& t) {
  const S aa = axis.squaredNorm();
  const Mat3<S> K = aa * Mat3<S>::Identity() - (S(1) + t * t) * (axis * axis.transpose());
  return centred_quadric<S>(K, apex, S(0));
}

/// 3x3 determinant of rows r[0..2] and columns c[0..2] of a 4x4 matrix.
template <class S> S minor3(const Mat4<S>& A, const int r[3], const int c[3]) {
  return A(r[0], c[0]) * (A(r[1], c[1]) * A(r[2], c[2]) - A(r[1], c[2]) * A(r[2], c[1])) -
         A(r[0], c[1]) * (A(r[1], c[0]) * A(r[2], c[2]) - A(r[1], c[2]) * A(r[2], c[0])) +
         A(r[0], c[2]) * (A(r[1], c[0]) * A(r[2], c[1]) - A(r[1], c[1]) * A(r[2], c[0]));
}

/// Adjugate of a 4x4 matrix (for a quadric: its dual, the quadric of tangent
/// planes). adj(A) = 0 exactly when rank A <= 2.
template <class S> Mat4<S> adjugate4(const Mat4<S>& A) {
  Mat4<S> adj;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      int r[3], c[3];
      for (int k = 0, n = 0; k < 4; ++k)
        if (k != j) r[n++] = k;
      for (int k = 0, n = 0; k < 4; ++k)
        if (k != i) c[n++] = k;
      const S m = minor3<S>(A, r, c);
      adj(i, j) = ((i + j) % 2 == 0) ? m : S(-m);
    }
  return adj;
}

/// A basis of the plane pi^T x = 0 (a 3-dimensional subspace of homogeneous
/// 4-vectors), division-free: with pivot k (pi_k != 0), the columns are
/// pi_k e_j - pi_j e_k (j != k). x = E s maps plane coordinates s to points of
/// the plane.
template <class S> Eigen::Matrix<S, 4, 3> plane_basis_at(const Vec4<S>& pi, int k) {
  Eigen::Matrix<S, 4, 3> E = Eigen::Matrix<S, 4, 3>::Zero();
  for (int j = 0, col = 0; j < 4; ++j) {
    if (j == k) continue;
    E(j, col) = pi(k);
    E(k, col) = -pi(j);
    ++col;
  }
  return E;
}

/// plane_basis_at with the pivot at the largest |pi_k|.
template <class S> Eigen::Matrix<S, 4, 3> plane_basis(const Vec4<S>& pi) {
  int k = 0;
  for (int i = 1; i < 4; ++i)
    if (qverify::less_than<S>(abs_of<S>(pi(k)), abs_of<S>(pi(i)))) k = i;
  return plane_basis_at<S>(pi, k);
}

/// Restriction of the quadric A to the plane with basis E: the 3x3 conic
/// K = E^T A E (summed term by term, for every scalar type).
template <class S> Mat3<S> conic_in_basis(const Mat4<S>& A, const Eigen::Matrix<S, 4, 3>& E) {
  Mat3<S> K;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      S sum(0);
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) sum = sum + E(a, i) * A(a, b) * E(b, j);
      K(i, j) = sum;
    }
  return K;
}

/// Restriction of the quadric A to the plane pi (basis: plane_basis(pi)).
template <class S> Mat3<S> conic_on_plane(const Mat4<S>& A, const Vec4<S>& pi) {
  return conic_in_basis<S>(A, plane_basis<S>(pi));
}

}  // namespace qverify
