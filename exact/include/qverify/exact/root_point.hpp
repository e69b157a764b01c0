#pragma once
/// \file root_point.hpp
/// Exact points with coordinates in a quadratic field Q(sqrt(delta)).
///
/// A rational line meets a quadric where a rational quadratic vanishes, so
/// its two intersection points are x = p +- sqrt(delta) q with p, q rational:
/// all four coordinates live in the *one* field Q(sqrt(delta)). Arithmetic in
/// that field is CGAL's `Sqrt_extension` (exact zero tests and signs).
///
/// CGAL's precondition that two operands share the same root is checked only
/// in debug builds (CGAL_precondition; with NDEBUG a mixed root silently gives
/// a wrong value). A RootPoint therefore keeps one delta, and
/// every value it produces is checked against it, in release builds too.

#include <qverify/core/scalar.hpp>
#include <qverify/exact/scalars.hpp>

#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Sqrt_extension.h>

#include <array>

#include <stdexcept>
#include <vector>

namespace qverify {

using Gmpq = CGAL::Gmpq;
/// a0 + a1 sqrt(root), exact.
using RootNumber = CGAL::Sqrt_extension<Gmpq, Gmpq, CGAL::Tag_true, CGAL::Tag_true>;

/// High precision (80 decimal digits) for *measuring* errors: independent of
/// the working precision chosen with --precision.
using Measure =
    boost::multiprecision::number<boost::multiprecision::mpfr_float_backend<80>, boost::multiprecision::et_off>;

Gmpq to_gmpq(const Rational& q);
Rational to_rational(const Gmpq& q);
Measure to_measure(const Rational& q);
/// The exact value of a finite Measure (a dyadic rational).
Rational exact_measure(const Measure& m);
/// The real value of a0 + a1 sqrt(r) to 80 digits, without cancellation:
/// where a0 and a1 sqrt(r) have opposite signs it is (a0^2 - a1^2 r) / (a0 - a1 sqrt(r)).
Measure to_measure(const RootNumber& v);

/// Unprotected CGAL intervals: the caller holds the FPU in round-upward mode
/// (CGAL::Protect_FPU_rounding<true>) for a whole loop of operations.
using FilterInterval = CGAL::Interval_nt<false>;
/// A certified enclosure of the four homogeneous coordinates of an exact point.
using PointEnclosure = std::array<FilterInterval, 4>;

class RootPoint {
 public:
  /// x = p + sqrt(delta) q, delta >= 0 (normalised to an integer: sqrt(n/d) = sqrt(n d)/d).
  RootPoint(const Vec4<Rational>& p, const Vec4<Rational>& q, const Rational& delta);
  /// x = p + sqrt(n) q for an integer n >= 0, taken as given: the form the
  /// constructor above normalises to, for code that has its radicand as an
  /// integer already (the sampler), without that constructor's divisions.
  /// Throws std::domain_error when n is negative or not an integer.
  static RootPoint with_integer_radicand(const Vec4<Rational>& p, const Vec4<Rational>& q, const Rational& n);
  /// p + sqrt(n) q and its conjugate p - sqrt(n) q for an integer n > 0, taken
  /// as given (as with_integer_radicand), the enclosures of p and of sqrt(n) q
  /// made once for both.
  static std::array<RootPoint, 2> conjugates(const Vec4<Rational>& p, const Vec4<Rational>& q, const Rational& n);

  const Vec4<Rational>& p() const { return p_; }
  const Vec4<Rational>& q() const { return q_; }
  const Rational& delta() const { return delta_; }
  /// Coordinates as field elements (all with root delta, or rational).
  std::array<RootNumber, 4> coords() const;
  /// The point M x (a rational linear map keeps the field).
  RootPoint mapped(const Mat4<Rational>& M) const;
  /// The points M x_k, M cleared to integers once for all of them.
  static std::vector<RootPoint> mapped(const std::vector<RootPoint>& xs, const Mat4<Rational>& M);
  /// x^T Q x, computed in Q(sqrt(delta)) with CGAL's arithmetic.
  RootNumber form(const Mat4<Rational>& Q) const;
  /// pi . x.
  RootNumber linear(const Vec4<Rational>& pi) const;
  /// Approximate Cartesian coordinates (x/w), to 80 digits; requires w != 0.
  Vec3<double> approx_cartesian() const;
  /// Certified enclosures of the coordinates, made once with the point: p_i
  /// enclosed, plus sign(q_i) times an enclosure of sqrt(delta) |q_i| (where
  /// delta is beyond the range of a double, sqrt(delta) enclosed in MPFR and
  /// multiplied by the exact q_i there, each step rounded outwards, so a huge
  /// delta with a small q is no harder than a small one). The floating filters in front of exact evaluations
  /// (measure_quadric, the verifier's point filter) start from it; an entry
  /// beyond the range of a double is an infinite bound, never a wrong one.
  const PointEnclosure& enclosure() const { return enclosure_; }

 private:
  struct normalised {};
  RootPoint(const Vec4<Rational>& p, const Vec4<Rational>& q, const Rational& delta, normalised)
      : p_(p), q_(q), delta_(delta) {
    enclose_coordinates();
  }
  RootPoint(const Vec4<Rational>& p, const Vec4<Rational>& q, const Rational& delta, const PointEnclosure& e)
      : p_(p), q_(q), delta_(delta), enclosure_(e) {}
  void check_root(const RootNumber& v) const;
  void enclose_coordinates();
  Vec4<Rational> p_, q_;
  Rational delta_;
  PointEnclosure enclosure_;
};

}  // namespace qverify
