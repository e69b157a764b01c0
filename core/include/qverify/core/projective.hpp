#pragma once
/// \file projective.hpp
/// Comparing projective objects (quadrics, planes) *up to scale* without ever
/// dividing by an entry: X ~ Y exactly when every 2x2 cross product
/// X_i Y_p - Y_i X_p vanishes, p being the pivot (largest |Y_p|).

#include <qverify/core/scalar.hpp>

namespace qverify {

/// Which factors `proportional` accepts.
enum class Factor { nonzero, positive };

/// Index (flattened, column-major) of the largest |entry|.
template <class Derived> Eigen::Index pivot_index(const Eigen::MatrixBase<Derived>& m) {
  using S = typename Derived::Scalar;
  Eigen::Index best = 0;
  S b = abs_of<S>(m(0));
  for (Eigen::Index i = 1; i < m.size(); ++i) {
    const S a = abs_of<S>(m(i));
    if (qverify::less_than<S>(b, a)) { b = a; best = i; }
  }
  return best;
}

/// Relative cross-product residual of X against Y as projective objects:
///   max_i |X_i Y_p - Y_i X_p| / (|X|_max |Y_p|),  p = pivot of Y.
/// Zero exactly when X = lambda Y for some lambda (any sign); for floating
/// inputs, a scale-free relative error. Returns 0 when both are zero and 1
/// when exactly one is.
template <class DX, class DY>
typename DX::Scalar cross_residual(const Eigen::MatrixBase<DX>& X, const Eigen::MatrixBase<DY>& Y) {
  using S = typename DX::Scalar;
  const Eigen::Index p = pivot_index(Y);
  const S yp = Y(p), xp = X(p);
  const S xs = max_abs(X), ys = abs_of<S>(yp);
  if (qverify::equals_zero<S>(xs) && qverify::equals_zero<S>(ys)) return S(0);
  if (qverify::equals_zero<S>(xs) || qverify::equals_zero<S>(ys)) return S(1);
  S worst(0);
  for (Eigen::Index i = 0; i < X.size(); ++i) {
    const S r = abs_of<S>(S(X(i) * yp - Y(i) * xp));
    if (qverify::less_than<S>(worst, r)) worst = r;
  }
  return worst / (xs * ys);
}

/// X = lambda Y with lambda != 0 (or > 0), compared by cross-multiplication:
/// exact for exact types; within `tol` (relative, see cross_residual) otherwise.
template <class DX, class DY>
bool proportional(const Eigen::MatrixBase<DX>& X, const Eigen::MatrixBase<DY>& Y, Factor factor,
                  const typename DX::Scalar& tol) {
  using S = typename DX::Scalar;
  const Eigen::Index p = pivot_index(Y);
  if (qverify::equals_zero<S>(max_abs(X)) != qverify::equals_zero<S>(max_abs(Y))) return false;
  if (factor == Factor::positive && sign_of<S>(X(p)) != sign_of<S>(Y(p))) return false;
  return !qverify::less_than<S>(tol, cross_residual(X, Y));
}

/// Symmetry law: Q^T = Q (exactly, or within tol * |Q|_max).
template <class S> bool is_symmetric(const Mat4<S>& Q, const S& tol) {
  return !qverify::less_than<S>(S(tol * max_abs(Q)), max_abs(Mat4<S>(Q - Q.transpose())));
}

}  // namespace qverify
