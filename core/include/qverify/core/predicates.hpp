#pragma once
/// \file predicates.hpp
/// The status words as *exact predicates* of the inputs (CGAL's "exact
/// predicates" discipline): a status is a property of the exact numbers A and L
/// (a double handed to the library is an exact dyadic rational), so it cannot
/// depend on units, placement or the precision asked for. No epsilon anywhere.
///
/// Every predicate is one generic function returning a Truth: `yes`, `no`, or
/// `unknown` when the scalar type cannot tell. It runs unchanged on
///  - exact types (rationals, the symbolic scalar): always yes or no;
///  - interval types (CGAL Interval_nt, MPFI): a sign is taken only when the
///    enclosure excludes the other signs;
///  - `Filtered<S>` for a rounding type S (float, double, long double, float128,
///    MPFR): the value computed in S with a running forward error bound; a sign
///    is taken only when |value| exceeds the bound.
/// An `unknown` is settled by the same function on exact rationals (the exact
/// layer: qverify/exact/statuses.hpp), the filter's fall-back.
///
/// The predicates (A a symmetric 4x4 quadric, L a homogeneous light):
///  - degenerate-quadric: rank A <= 2, i.e. adj A = 0 (every 3x3 minor zero);
///  - light-on-surface: L^T A L = 0;
///  - no-real-silhouette: the conic cut from A by the polar plane pi = A L is
///    definite (its 3x3 matrix K = E^T A E, E a basis of pi, has leading minors
///    m2 > 0 and sign m1 = sign m3 != 0, Sylvester): no real terminator point.

#include <qverify/core/quadric.hpp>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <optional>

namespace qverify {

enum class Truth { no, yes, unknown };

/// A value computed in the rounding type S together with the magnitude of
/// the same expression evaluated on absolute values (`mag`) and the depth of
/// the evaluation (`depth`, roundings along the longest path). For sums and
/// products, |value - exact| <= gamma_depth * exact|.|-value, and the computed
/// `mag` is within gamma_depth of the exact one; `bound()` returns
/// 2 (depth + 1) u mag, which covers both for depth u < 1/4. A product of two
/// non-zero magnitudes below the smallest normal number sets `tiny`
/// (underflow: the bound no longer holds, the sign is left unknown).
template <class S> struct Filtered {
  S value = S(0), mag = S(0);
  int depth = 0;
  bool tiny = false;

  Filtered() = default;
  Filtered(const S& x) : value(x), mag(x < S(0) ? S(-x) : x) {}  // NOLINT: exact inputs convert implicitly
  Filtered(const S& v, const S& m, int d, bool t) : value(v), mag(m), depth(d), tiny(t) {}

  static S unit_roundoff() { return std::numeric_limits<S>::epsilon() / S(2); }
  /// Certified bound of |value - exact value|.
  S bound() const { return S(2 * (depth + 1)) * unit_roundoff() * mag; }
  /// Inputs and intermediate results must stay finite for the bound to hold.
  bool reliable() const { return !tiny && mag <= std::numeric_limits<S>::max(); }
  /// Certain sign, or nullopt.
  std::optional<int> sign() const {
    if (!reliable()) return std::nullopt;
    if (mag == S(0)) return 0;  // every term an exact zero
    const S b = bound();
    if (value > b) return 1;
    if (value < -b) return -1;
    return std::nullopt;
  }

  friend Filtered operator+(const Filtered& a, const Filtered& b) {
    return {a.value + b.value, a.mag + b.mag, std::max(a.depth, b.depth) + 1, a.tiny || b.tiny};
  }
  friend Filtered operator-(const Filtered& a, const Filtered& b) {
    return {a.value - b.value, a.mag + b.mag, std::max(a.depth, b.depth) + 1, a.tiny || b.tiny};
  }
  friend Filtered operator*(const Filtered& a, const Filtered& b) {
    const S m = a.mag * b.mag;
    const bool under = a.mag != S(0) && b.mag != S(0) && m < std::numeric_limits<S>::min();
    return {a.value * b.value, m, a.depth + b.depth + 1, a.tiny || b.tiny || under};
  }
  Filtered operator-() const { return {S(-value), mag, depth, tiny}; }
  Filtered& operator+=(const Filtered& b) { return *this = *this + b; }
  Filtered& operator-=(const Filtered& b) { return *this = *this - b; }
  Filtered& operator*=(const Filtered& b) { return *this = *this * b; }
  /// Only the certain answers are true (the core's interval discipline).
  friend bool operator==(const Filtered& a, const Filtered& b) { return (a - b).sign() == std::optional<int>(0); }
  friend bool operator!=(const Filtered& a, const Filtered& b) { return !(a == b); }
};

}  // namespace qverify

namespace Eigen {
/// Filtered values as Eigen scalars (only storage and entrywise arithmetic are used).
template <class S> struct NumTraits<qverify::Filtered<S>> : GenericNumTraits<qverify::Filtered<S>> {
  using Real = qverify::Filtered<S>;
  using NonInteger = qverify::Filtered<S>;
  using Literal = qverify::Filtered<S>;
  enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 1, ReadCost = 4, AddCost = 8, MulCost = 8 };
};
}  // namespace Eigen

namespace qverify {

/// Decisions on Filtered values are certain or false, like an interval's.
template <class S> struct ScalarOps<Filtered<S>> {
  using F = Filtered<S>;
  static constexpr bool interval = true;
  static bool exact() { return false; }
  static bool less(const F& a, const F& b) { return (b - a).sign() == std::optional<int>(1); }
  static bool is_zero(const F& a) { return a.sign() == std::optional<int>(0); }
  static F abs(const F& x) { return x.value < S(0) ? -x : x; }
  static bool finite(const F& x) { return x.reliable(); }
};

/// Where a predicate on S-valued inputs is evaluated: S itself for exact and
/// interval types, Filtered<S> for a rounding type.
template <class S> using PredicateScalar =
    std::conditional_t<std::numeric_limits<S>::is_specialized && !std::numeric_limits<S>::is_exact &&
                           !ScalarOps<S>::interval,
                       Filtered<S>, S>;

/// The certain sign of x (-1, 0, +1), or nullopt when the type cannot tell.
template <class S> std::optional<int> certain_sign(const S& x) {
  if (qverify::less_than<S>(S(0), x)) return 1;
  if (qverify::less_than<S>(x, S(0))) return -1;
  if (qverify::equals_zero<S>(x)) return 0;
  return std::nullopt;
}

/// Entrywise conversion into the predicate scalar (exact: each input is its own value).
template <class P, class S, int R, int C> Eigen::Matrix<P, R, C> to_predicate(const Eigen::Matrix<S, R, C>& m) {
  Eigen::Matrix<P, R, C> out;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = P(m(i));
  return out;
}

/// 3x3 determinant by cofactors along the first row (a fixed evaluation for every scalar).
template <class S> S det3(const Mat3<S>& K) {
  return K(0, 0) * (K(1, 1) * K(2, 2) - K(1, 2) * K(2, 1)) - K(0, 1) * (K(1, 0) * K(2, 2) - K(1, 2) * K(2, 0)) +
         K(0, 2) * (K(1, 0) * K(2, 1) - K(1, 1) * K(2, 0));
}

/// degenerate-quadric: rank A <= 2, i.e. adj A = 0.
template <class S> Truth degenerate_quadric(const Mat4<S>& A) {
  const Mat4<S> adj = adjugate4<S>(A);
  bool all_zero = true;
  for (Eigen::Index i = 0; i < adj.size(); ++i) {
    const auto s = certain_sign<S>(adj(i));
    if (s && *s != 0) return Truth::no;
    if (!s) all_zero = false;
  }
  return all_zero ? Truth::yes : Truth::unknown;
}

/// light-on-surface: L^T A L = 0.
template <class S> Truth light_on_surface(const Mat4<S>& A, const Vec4<S>& L) {
  const auto s = certain_sign<S>(ordered_dot<S, 4>(L, ordered_product<S>(A, L)));
  if (!s) return Truth::unknown;
  return *s == 0 ? Truth::yes : Truth::no;
}

/// The leading principal minor of order i (1 <= i <= k) of a k x k matrix, by cofactors (a fixed
/// evaluation for every scalar, no division).
template <class S, int k> S leading_minor(const Eigen::Matrix<S, k, k>& M, int i) {
  static_assert(k >= 1 && k <= 4, "leading minors of orders 1 to 4");
  if (i == 1) return M(0, 0);
  if constexpr (k >= 2) {
    if (i == 2) return S(M(0, 0) * M(1, 1) - M(0, 1) * M(1, 0));
  }
  if constexpr (k >= 3) {
    if (i == 3) return det3<S>(Mat3<S>(M.template topLeftCorner<3, 3>()));
  }
  if constexpr (k == 4) {
    const Mat4<S> adj = adjugate4<S>(M);
    return S(M(0, 0) * adj(0, 0) + M(0, 1) * adj(1, 0) + M(0, 2) * adj(2, 0) + M(0, 3) * adj(3, 0));
  }
  return S(0);  // (not reached for 1 <= i <= k)
}

/// Sylvester's test of a symmetric form M (k x k, k <= 4): +1 where it is positive definite (its
/// leading principal minors m_i all positive), -1 negative definite (sign m_i = (-1)^i), 0 neither;
/// nullopt where the signs the scalar can tell leave both open (a rounding or an interval scalar;
/// an exact one always tells). A definite conic or quadric has no real point, not even at infinity.
/// The one test of definiteness in the project: the no-real-silhouette predicate (conic_definite),
/// the sampler's sections and quadrics without real points, eval's ellipsoids and frames.
template <class S, int k> std::optional<int> definiteness(const Eigen::Matrix<S, k, k>& M) {
  bool positive = true, negative = true, known = true;
  for (int i = 1; i <= k; ++i) {
    const auto s = certain_sign<S>(leading_minor<S, k>(M, i));
    if (!s) {
      known = false;
      continue;
    }
    positive = positive && *s > 0;
    negative = negative && *s == (i % 2 ? -1 : 1);
    if (!positive && !negative) return 0;
  }
  if (!known) return std::nullopt;
  return positive ? 1 : negative ? -1 : 0;
}

/// The conic x^T K x = 0 has no real point: K is definite (definiteness).
template <class S> Truth conic_definite(const Mat3<S>& K) {
  const auto d = definiteness<S, 3>(K);
  if (!d) return Truth::unknown;
  return *d != 0 ? Truth::yes : Truth::no;
}

/// no-real-silhouette: the conic A ∩ {pi . x = 0}, pi = A L, is definite.
/// Definiteness does not depend on the basis E of the plane (congruence), so
/// any certainly non-zero pi_k serves as the pivot of E.
template <class S> Truth silhouette_empty(const Mat4<S>& A, const Vec4<S>& L) {
  const Vec4<S> pi = ordered_product<S>(A, L);
  int k = -1;
  bool all_zero = true;
  for (int i = 0; i < 4; ++i) {
    const auto s = certain_sign<S>(pi(i));
    if (s && *s != 0) { k = i; break; }
    if (!s) all_zero = false;
  }
  if (k < 0) return all_zero ? Truth::no : Truth::unknown;  // pi = 0: the "plane" is everything
  return conic_definite<S>(conic_in_basis<S>(A, plane_basis_at<S>(pi, k)));
}

/// The decided flags of a predicate evaluation and the ones it could not decide.
struct StatusDecision {
  unsigned flags = 0, undecided = 0;
  bool decided() const { return undecided == 0; }
};

}  // namespace qverify
