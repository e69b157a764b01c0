#pragma once
/// \file mirror_division_free.hpp
/// The mirror image of eq. (11) without a division, for exact integer scalars
/// (128-bit integers, WideInt, GMP integers), in the rank-one form.
///
/// mirror.hpp writes B = M^T A M in rank-one form with h = (n, 0) / (n.n): one
/// division, right for floating point and rationals. An integer type has no
/// division; scaled_mirror_matrix gives (n.n) M, and (n.n)^2 B = M'^T A M' then
/// takes two 4x4 products (128 multiplications). Multiplying the rank-one form
/// through by k^2, k = n.n, instead:
///   a' = A (2n)                (A's first three columns; 12 products)
///   beta' = n . a'_xyz         (= n^T A 2n)
///   c' = k a' - beta' w        (= k^2 c of mirror.hpp's mirror_image_from)
///   k^2 B = k^2 A - w c'^T - c' w^T,
/// w = (n, d) the mirror plane: 57 products, and exactly the same matrix as
/// mirror_image(A, scaled_mirror_matrix(plane)) (tests/verify/test_point_filter.cpp checks
/// the identity on rationals, 128-bit integers and WideInt).
///
/// Bit bound (for fixed-width integers): with |A| < 2^bA and |w| < 2^bL every
/// intermediate and the result stay below 2^(bA + 4 bL + 8).

#include <qverify/core/scalar.hpp>

namespace qverify {

/// (n.n)^2 times the mirror image of A in the plane w = (n, d), division-free.
/// Precondition: n != 0.
template <class S> Mat4<S> mirror_image_division_free(const Mat4<S>& A, const Vec4<S>& plane) {
  const Vec3<S> n = plane.template head<3>();
  const Vec3<S> n2(n(0) + n(0), n(1) + n(1), n(2) + n(2));
  const S k = ordered_dot<S, 3>(n, n);
  Vec4<S> a;
  for (int i = 0; i < 4; ++i) a(i) = ordered_dot<S, 3>(A.row(i).template head<3>().transpose(), n2);
  const S beta = ordered_dot<S, 3>(n, a.template head<3>());
  Vec4<S> c;
  for (int i = 0; i < 4; ++i) c(i) = k * a(i) - beta * plane(i);
  const S k2 = k * k;
  return symmetric_from<S>([&](int i, int j) { return S(k2 * A(i, j) - (plane(i) * c(j) + c(i) * plane(j))); });
}

}  // namespace qverify
