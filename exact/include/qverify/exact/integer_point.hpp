#pragma once
/// \file integer_point.hpp
/// Exact points of Q(sqrt delta) with their denominators cleared, for
/// evaluating forms on integers (no gcd per operation, as rational
/// arithmetic has) and rounding only the final values.
///
/// x = p + sqrt(delta) q (RootPoint, delta a non-negative integer) is
///   x = (P Dv + sqrt(delta) V Dp) / (Dp Dv),   P = p Dp, V = q Dv integers,
/// Dp, Dv > 0 the least common denominators of p and q. For an integer
/// matrix Qi (Q = Qi / DQ) with y = Qi P, z = Qi V, a = P.y, b = V.z, c = P.z + V.y:
///   x^T Q x = ((a Dv^2 + delta b Dp^2) + sqrt(delta) c Dp Dv) / (Dp^2 Dv^2 DQ),
///   (Q x)_i = (y_i Dv + sqrt(delta) z_i Dp) / (Dp Dv DQ).
/// Every value is u + v sqrt(delta) over a positive integer; root_magnitude
/// rounds its absolute value to 80 digits without cancellation.

#include <qverify/exact/root_point.hpp>

#include <boost/multiprecision/gmp.hpp>

#include <array>
#include <optional>

namespace qverify {

using BigInt = boost::multiprecision::mpz_int;

/// GMP's integer behind a BigInt, for the in-place calls Boost has no form of
/// (mpz_addmul, mpz_submul, mpz_divexact): no temporaries, no allocation once grown.
inline mpz_ptr mpz(BigInt& x) { return x.backend().data(); }
inline mpz_srcptr mpz(const BigInt& x) { return x.backend().data(); }

/// The integer vector v D with D > 0 the least common multiple of v's denominators.
void clear_denominators(const Vec4<Rational>& v, std::array<BigInt, 4>& out, BigInt& D);
/// The integer matrix Q D with D > 0 the least common multiple of Q's denominators (row-major).
void clear_denominators(const Mat4<Rational>& Q, std::array<BigInt, 16>& out, BigInt& D);

/// v or Q times the positive rational that makes it a primitive integer array (denominators
/// cleared, the entries' gcd divided out; zero stays zero): one form for all of its positive
/// multiples, the same quadric, plane, point or direction. The sampler works on these
/// (sampling.hpp), so that 3 A, or a light written with other denominators, gets the same points
/// in the same representation.
void primitive_integers(const Vec4<Rational>& v, std::array<BigInt, 4>& out);
void primitive_integers(const Mat4<Rational>& Q, std::array<BigInt, 16>& out);

/// A RootPoint on integers (see the file comment).
struct IntegerPoint {
  explicit IntegerPoint(const RootPoint& x);
  std::array<BigInt, 4> P, V;
  BigInt Dp, Dv, d;
  bool rational = true;  ///< V = 0 (or delta = 0): x = P / Dp
  bool square = false;   ///< delta = r^2 for an integer r (then x is rational too, in another form)

  /// x_i = (u_i + sqrt(delta) v_i) / den: u_i = P_i Dv, v_i = V_i Dp, den = Dp Dv.
  BigInt u(int i) const { return P[static_cast<std::size_t>(i)] * Dv; }
  BigInt v(int i) const { return V[static_cast<std::size_t>(i)] * Dp; }
  BigInt den() const { return Dp * Dv; }
  /// sqrt(delta) to 80 digits, computed on first use and then kept: every value
  /// of the point rounded to 80 digits needs it, and it costs more than the rest
  /// of such a rounding. (Not thread-safe: an IntegerPoint belongs to one thread.)
  const Measure& root() const;
  /// x_i to 80 digits, with its exact sign.
  Measure coordinate(int i) const;
  /// |x_i| to 80 digits.
  Measure magnitude(int i) const;
  /// x_i / x_3 - c (a Cartesian offset from a rational point) to 80 digits, from the exact
  /// difference: a point 1e-100 from c and 3 from the origin, rounded first, was its rounding noise.
  Measure offset(int i, const Rational& c) const;

 private:
  mutable std::optional<Measure> root_;
};

/// out = u^2 - v^2 d exactly (`t` is scratch): the norm of u + v sqrt(d), whose sign
/// tells |u| from |v| sqrt(d) and whose value lets |u + v sqrt(d)| be rounded
/// without cancellation.
void root_norm(BigInt& out, const BigInt& u, const BigInt& v, const BigInt& d, BigInt& t);
/// The exact sign of u + v sqrt(d) (d >= 0).
int root_sign(const BigInt& u, const BigInt& v, const BigInt& d);
/// u + v sqrt(d) == 0 exactly (d >= 0; `square`: d is a perfect square, else a
/// non-zero v already decides).
bool root_is_zero(const BigInt& u, const BigInt& v, const BigInt& d, bool square);
/// |u + v sqrt(d)| / den to 80 digits (den > 0, d >= 0; root = sqrt(d) to 80 digits, as
/// IntegerPoint::root() gives it), without cancellation: where u and v sqrt(d) have
/// opposite signs, |u^2 - v^2 d| / ((|u| + |v| sqrt(d)) den).
Measure root_magnitude(const BigInt& u, const BigInt& v, const BigInt& d, const Measure& root, const BigInt& den);
/// (u + v sqrt(d)) / den to 80 digits, with its exact sign (root_magnitude signed).
Measure root_value(const BigInt& u, const BigInt& v, const BigInt& d, const Measure& root, const BigInt& den);

}  // namespace qverify
