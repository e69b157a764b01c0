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

// GCC 12: <x86intrin.h> (pulled in by <experimental/simd>, pack.hpp) leaves a new
// optimisation node behind its target pragmas; functions defined before it and
// functions defined after it then refuse to inline into each other ("optimization
// level attribute mismatch"), and the interval packs ran 5x slower. Including it
// first puts every qverify function on the same side.
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#include <x86intrin.h>
#endif

#include <Eigen/Core>
#include <Eigen/LU>        // determinant(), inverse()
#include <Eigen/Geometry>  // cross()

namespace qverify {

template <class S> using Vec3 = Eigen::Matrix<S, 3, 1>;
template <class S> using Vec4 = Eigen::Matrix<S, 4, 1>;
template <class S> using Mat3 = Eigen::Matrix<S, 3, 3>;
template <class S> using Mat4 = Eigen::Matrix<S, 4, 4>;

/// The decisions the core takes on scalars. The primary template serves
/// totally ordered types (floating point, rationals, the symbolic scalar);
/// interval types specialise it (exact/interval.hpp) so that a comparison is
/// true only when it is *certain*, and never throws.
template <class S, class Enable = void> struct ScalarOps {
  static constexpr bool interval = false;
  /// Does S round? Exact types have NumTraits epsilon 0.
  static bool exact() { return Eigen::NumTraits<S>::epsilon() == S(0); }
  static bool less(const S& a, const S& b) { return a < b; }
  static bool is_zero(const S& a) { return a == S(0); }
  static S abs(const S& x) { return x < S(0) ? S(-x) : x; }
  /// Not NaN and not beyond the largest finite value (always true when exact).
  static bool finite(const S& x) {
    if (!(x == x)) return false;
    return exact() || !(Eigen::NumTraits<S>::highest() < abs(x));
  }
};

/// True when `S` does not round (NumTraits epsilon is zero).
template <class S> inline bool is_exact() { return ScalarOps<S>::exact(); }

/// a < b (for intervals: certainly).
template <class S> inline bool less_than(const S& a, const S& b) { return ScalarOps<S>::less(a, b); }

/// x == 0 (for intervals: certainly).
template <class S> inline bool equals_zero(const S& x) { return ScalarOps<S>::is_zero(x); }

/// |x| for any scalar.
template <class S> inline S abs_of(const S& x) { return ScalarOps<S>::abs(x); }

/// -1, 0 or +1 (0 for an interval whose sign is not certain).
template <class S> inline int sign_of(const S& x) { return qverify::less_than<S>(S(0), x) - qverify::less_than<S>(x, S(0)); }

/// Largest absolute entry, the scale used by every tolerance of the core.
template <class Derived>
inline typename Derived::Scalar max_abs(const Eigen::MatrixBase<Derived>& m) {
  using S = typename Derived::Scalar;
  S best(0);
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      S a = abs_of<S>(m(i, j));
      if (qverify::less_than<S>(best, a)) best = a;
    }
  return best;
}

/// a . b summed left to right, ((a0 b0 + a1 b1) + a2 b2) + ...: one evaluation
/// order for every scalar type. Eigen's own dot products and matrix-vector
/// products reorder the sum when they vectorise (double) and not otherwise
/// (a SIMD pack as the scalar, pack.hpp), so the direct formulas use this and
/// a batch computed W items at a time is bitwise the single-item result.
template <class S, int N> inline S ordered_dot(const Eigen::Matrix<S, N, 1>& a, const Eigen::Matrix<S, N, 1>& b) {
  S sum = a(0) * b(0);
  for (int k = 1; k < N; ++k) sum += a(k) * b(k);  // in place where a type has it (DigitPack: no copy of a wide sum)
  return sum;
}

/// A x with every row summed by ordered_dot.
template <class S> inline Vec4<S> ordered_product(const Mat4<S>& A, const Vec4<S>& x) {
  Vec4<S> y;
  for (int i = 0; i < 4; ++i) y(i) = ordered_dot<S, 4>(A.row(i).transpose(), x);
  return y;
}

/// A symmetric 4x4 matrix from its upper triangle: m(i, j) = m(j, i) = f(i, j)
/// for i <= j (ten evaluations instead of sixteen; exactly symmetric).
/// No self-assignment on the diagonal: Boost's mpfi backend turns x = x into NaN.
template <class S, class F> inline Mat4<S> symmetric_from(F&& f) {
  Mat4<S> m;
  for (int i = 0; i < 4; ++i) {
    m(i, i) = f(i, i);
    for (int j = i + 1; j < 4; ++j) m(i, j) = m(j, i) = f(i, j);
  }
  return m;
}

/// N^T A N for a symmetric A (a change of frame of a quadric): symmetric in exact arithmetic, and
/// made so in every scalar type as the symmetric part of the dense product, (X + X^T) / 2. The
/// product rounds entries (i, j) and (j, i) apart: the paper route's P and R in float came out 2e-8
/// and 6e-8 of their largest entry from symmetric, which verify fails. The symmetric part is what
/// x^T X x reads, so the geometry is the product's: keeping one triangle instead (or computing it
/// alone) lost the two roundings' averaging and measured up to twice the geometric error on far
/// mirrors and in the float paper route (tests/golden, stress-mirror-far). Halves first, then adds:
/// (a + b) / 2 overflows where both are above half the largest finite value. Exact types need none
/// of it (their product is symmetric).
template <class S> inline Mat4<S> congruence(const Mat4<S>& A, const Mat4<S>& N) {
  const Mat4<S> X = N.transpose() * A * N;
  if (ScalarOps<S>::exact()) return X;
  return symmetric_from<S>([&](int i, int j) { return i == j ? X(i, i) : S(X(i, j) / S(2) + X(j, i) / S(2)); });
}

/// u v^T + v u^T: the quadric of the plane pair {u = 0} ∪ {v = 0}.
/// (Twice the symmetrised outer product; results here are defined up to a
/// non-zero factor, so the 1/2 is left out and no division is needed.)
template <class S> inline Mat4<S> plane_pair(const Vec4<S>& u, const Vec4<S>& v) {
  return symmetric_from<S>([&](int i, int j) { return S(u(i) * v(j) + v(i) * u(j)); });
}

}  // namespace qverify
