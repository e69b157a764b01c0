#pragma once
/// \file scalar.hpp
/// Scalar-generic vocabulary of qverify's core: fixed-size Eigen types and the
/// few scalar helpers the formulas need.
///
/// Every function of the core is a template on the scalar type `S`. It must
/// work unchanged for `float`, `double`, `long double`, Boost.Multiprecision
/// floats (float128, MPFR), interval types and exact rationals. Hence:
///  - no decimal literals: write `S(1) / S(2)`, never `0.5`;
///  - exactness is read from `Eigen::NumTraits<S>::epsilon()`: an exact type
///    has epsilon 0, so every tolerance `k * epsilon` collapses to an exact
///    zero test and "approximately equal" becomes "equal".

#include <Eigen/Core>
#include <Eigen/LU>        // determinant(), inverse()
#include <Eigen/Geometry>  // cross()

namespace qverify {

template <class S> using Vec3 = Eigen::Matrix<S, 3, 1>;
template <class S> using Vec4 = Eigen::Matrix<S, 4, 1>;
template <class S> using Mat3 = Eigen::Matrix<S, 3, 3>;
template <class S> using Mat4 = Eigen::Matrix<S, 4, 4>;

/// True when `S` does not round (NumTraits epsilon is zero).
template <class S> inline bool is_exact() { return Eigen::NumTraits<S>::epsilon() == S(0); }

/// |x| for any scalar (found by ADL for multiprecision types).
template <class S> inline S abs_of(const S& x) { return x < S(0) ? S(-x) : x; }

/// -1, 0 or +1.
template <class S> inline int sign_of(const S& x) { return (S(0) < x) - (x < S(0)); }

/// Largest absolute entry, the scale used by every tolerance of the core.
template <class Derived>
inline typename Derived::Scalar max_abs(const Eigen::MatrixBase<Derived>& m) {
  using S = typename Derived::Scalar;
  S best(0);
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      S a = abs_of<S>(m(i, j));
      if (best < a) best = a;
    }
  return best;
}

/// Relative tolerance of the status decisions of the core: `64 * epsilon`
/// (zero, i.e. exact tests, for exact types). A quantity q computed from data of
/// scale `s` is declared zero when `|q| <= status_tolerance<S>() * s`.
template <class S> inline S status_tolerance() { return S(64) * Eigen::NumTraits<S>::epsilon(); }

/// `|q| <= tol * scale` with the core's status tolerance; `q == 0` for exact types.
template <class S> inline bool negligible(const S& q, const S& scale) {
  return !(status_tolerance<S>() * scale < abs_of<S>(q));
}

/// u v^T + v u^T: the quadric of the plane pair {u = 0} ∪ {v = 0}.
/// (Twice the symmetrised outer product; results here are defined up to a
/// non-zero factor, so the 1/2 is left out and no division is needed.)
template <class S> inline Mat4<S> plane_pair(const Vec4<S>& u, const Vec4<S>& v) {
  return u * v.transpose() + v * u.transpose();
}

}  // namespace qverify
