#pragma once
/// \file point_filter.hpp
/// The verifier's point check, filtered: certified floating evaluation first,
/// exact only where it cannot decide.
///
/// The rule (accuracy.hpp, the one behind `verify`'s verdict): an exact point
/// x = p + sqrt(d) q (RootPoint) passes a floating candidate quadric Q when its
/// first-order distance
///   |x^T Q x| / (|w| 2 |(Q x)_xyz|)      (plane pi: |pi.x| / (|w| |pi_xyz|))
/// is at most T * size (T the accuracy target, size the object size), or its
/// second-order distance sqrt(|f| / kappa) / |w| is (a point of Q lies that
/// close: measure_quadric), or when x^T Q x is exactly 0; a point off Q where
/// neither exists fails.
/// Where the object has no size (a terminator that is a single point) the
/// rule is the relative residual |x^T Q x| / (|Q|_F |x|^2) <= T instead.
///
/// The surface and its gradient are the candidate's symmetric part's: a candidate that is not exactly
/// symmetric (verify accepts an asymmetry within the target) goes to stage 3 at every point, which
/// measures that part (measure_quadric).
/// Three stages decide it, each certified, each only where the one before
/// could not:
///  1. the filter: the same inequality squared (no square root) in interval
///     arithmetic (CGAL::Interval_nt, the FPU rounding upward) from a certified
///     enclosure of x (each p_i enclosed, sqrt(d q_i^2) enclosed:
///     `enclose_point`, computed once per point when it is sampled) and an
///     enclosure of T * size. It answers pass or fail only when the whole
///     interval of |f|^2 lies on one side of the whole interval of the bound, so
///     a decision is the exact one; otherwise (the candidate's error within its
///     own rounding of the boundary: an ill-conditioned quadric, a far frame; a
///     huge or non-finite enclosure) it answers `undecided`;
///  2. exact integers: with the point's denominators cleared once
///     (ClearedPoints) and the candidate's doubles as integers times a power of
///     two, f = F0 + F1 sqrt(d), (Q x)_i and w are exact integer pairs; their
///     magnitudes are enclosed in MPFR at 128 bits with directed rounding
///     (exact/root_enclosure.hpp: a - b sqrt(d) directly where that is tight,
///     else as (a^2 - b^2 d) / (a + b sqrt(d)), no cancellation), so this
///     stage decides everything but points within about 1e-15 of the
///     boundary (the enclosure of T * size is one ulp wide);
///  3. the verifier's own measure at that one point (measure_quadric /
///     measure_plane, Q(sqrt d) and 80 digits).
/// By the distance rule, stage 1 decides a quadric's point `fail` only where the
/// second order cannot pass it either (4 |grad|^2 >= |f| |K|_F, K the spatial
/// part: no curvature exceeds |K|_F), and stage 2 likewise: the others go on to
/// stage 3, whose second-order distance may pass them.
/// `exact_fallbacks` in reports counts the pairs stage 1 left to stages 2 and 3
/// (`measured`: those that reached 3). tests/verify/test_point_filter.cpp checks the
/// decisions of stages 1 and 2 against stage 3 on random and adversarial points.
///
/// Proof mode (exact candidates: every residual must be exactly 0) has its own
/// fast path on the same cleared points: x^T Q x = 0 is decided on GMP integers
/// (a + d b = 0 and c = 0 for a + d b + 2 sqrt(d) c, or the rational root when
/// d is a square), without the gcds of rational arithmetic.

#include <qverify/exact/integer_point.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/eval/accuracy.hpp>

#include <boost/multiprecision/gmp.hpp>

#include <CGAL/Interval_nt.h>

#include <array>
#include <cstddef>
#include <vector>

namespace qverify {

/// Sets the FPU to round upward for its lifetime (and restores the mode).
using FilterRounding = CGAL::Protect_FPU_rounding<true>;

/// A certified enclosure of the homogeneous coordinates of an exact point.
struct EnclosedPoint {
  PointEnclosure x;
};

/// The enclosure of x = p + sqrt(d) q that the point carries (RootPoint::enclosure).
inline EnclosedPoint enclose_point(const RootPoint& x) { return EnclosedPoint{x.enclosure()}; }

/// The accuracy target of one item's points: the distance bound T * size, or
/// the relative residual rule where the size is not positive.
struct FilterTarget {
  FilterTarget(double accuracy, const Measure& size);
  double accuracy;
  Measure T, size;
  bool residual_rule;    ///< size not > 0: |f| <= T |Q|_F |x|^2
  FilterInterval bound;  ///< encloses T * size (residual rule: T)
};

enum class FilterVerdict : unsigned char { pass, fail, undecided };

/// The certified floating decision at one point. The FPU must round upward
/// (hold a FilterRounding); the *_guarded forms set it themselves.
FilterVerdict filter_quadric(const EnclosedPoint& x, const Mat4<double>& Q, const FilterTarget& t);
FilterVerdict filter_plane(const EnclosedPoint& x, const Vec4<double>& pi, const FilterTarget& t);
FilterVerdict filter_quadric_guarded(const EnclosedPoint& x, const Mat4<double>& Q, const FilterTarget& t);
FilterVerdict filter_plane_guarded(const EnclosedPoint& x, const Vec4<double>& pi, const FilterTarget& t);

/// The exact decision at one point: the verifier's measure (measure_quadric /
/// measure_plane on this point, relative(), compared with T), no filter.
bool exact_quadric_passes(const RootPoint& x, const Mat4<Rational>& Q, const FilterTarget& t);
bool exact_plane_passes(const RootPoint& x, const Vec4<Rational>& pi, const FilterTarget& t);

/// What a run of checks did.
struct FilterCounts {
  std::size_t checked = 0;    ///< (point, quadric) pairs
  std::size_t failed = 0;     ///< pairs beyond the target
  std::size_t fallbacks = 0;  ///< pairs the interval filter left to exact arithmetic (stages 2 and 3)
  std::size_t measured = 0;   ///< of those, pairs decided by the verifier's 80-digit measure (stage 3)
  FilterCounts& operator+=(const FilterCounts& o) {
    checked += o.checked, failed += o.failed, fallbacks += o.fallbacks, measured += o.measured;
    return *this;
  }
};

// --------------------------------------------------- exact integers (stage 2, proof mode)

/// A candidate with its denominators cleared (a positive factor: neither the
/// zero test nor the distance rule sees it). A double candidate is exactly
/// integers times a power of two.
struct IntegerQuadric {
  explicit IntegerQuadric(const Mat4<Rational>& Q);
  explicit IntegerQuadric(const Mat4<double>& Q);
  std::array<BigInt, 16> q;  ///< row-major
  BigInt spatial4;           ///< 4 |K|_F^2 of q's symmetrised spatial part K (stage 2's second-order test)
};
struct IntegerPlane {
  explicit IntegerPlane(const Vec4<Rational>& pi);
  explicit IntegerPlane(const Vec4<double>& pi);
  std::array<BigInt, 4> pi;
};

/// Exact points with denominators cleared once: x = P / Dp + sqrt(d) V / Dv
/// with integer vectors P, V (d the point's integer radicand). With
/// a = P^T Q P, b = V^T Q V, c = P^T Q V (Q symmetric, as every candidate the
/// verifier accepts; measure_quadric also takes non-symmetric forms):
///   (Dp Dv)^2 x^T Q x = (a Dv^2 + b d Dp^2) + sqrt(d) (2 c Dp Dv),
///   Dp Dv (Q x)_i = (Q P)_i Dv + sqrt(d) (Q V)_i Dp,  Dp Dv w = P_3 Dv + sqrt(d) V_3 Dp;
/// x^T Q x = 0 exactly when a Dv^2 + b d Dp^2 = 0 and c = 0 (d not a square),
/// or a Dv^2 + b d Dp^2 + 2 r c Dp Dv = 0 (d = r^2).
class ClearedPoints {
 public:
  explicit ClearedPoints(const std::vector<RootPoint>& points);
  std::size_t size() const { return pts_.size(); }
  /// Proof mode: x_k^T Q x_k == 0 exactly; pi . x_k == 0 exactly.
  bool on_quadric(std::size_t k, const IntegerQuadric& Q) const;
  bool on_plane(std::size_t k, const IntegerPlane& pi) const;
  /// Every point, proof mode (failed = points off the candidate; no fallbacks).
  FilterCounts check_quadric(const IntegerQuadric& Q) const;
  FilterCounts check_plane(const IntegerPlane& pi) const;
  /// Stage 2: the distance rule decided from the exact integers (undecided
  /// within about 1e-15 of the boundary, and always under the residual rule).
  FilterVerdict decide_quadric(std::size_t k, const IntegerQuadric& Q, const FilterTarget& t) const;
  FilterVerdict decide_plane(std::size_t k, const IntegerPlane& pi, const FilterTarget& t) const;
  /// Bytes of the points' integers (limbs), for reports.
  std::size_t limb_bytes() const;

 private:
  struct Point {
    std::array<BigInt, 4> P, V;
    BigInt Dp, Dv, d;
    bool rational = true;  ///< V = 0 (or d = 0): x = P / Dp
    bool square = false;   ///< d is a perfect square r^2
    BigInt ka, kb, m;      ///< Dv^2, d Dp^2, 2 Dp Dv
    BigInt kc;             ///< 2 r Dp Dv (d = r^2)
    BigInt la, lb;         ///< Dv, r Dp (d = r^2)
    BigInt w0, w1;         ///< P_3 Dv, V_3 Dp
  };
  std::vector<Point> pts_;
};

/// The exact points of one item (in the candidate's frame), their enclosures,
/// their cleared integers and the item's target: made once, checked against
/// any number of candidates.
struct FilterPoints {
  FilterPoints(std::vector<RootPoint> points, const Measure& size, double accuracy);
  std::vector<RootPoint> exact;
  std::vector<EnclosedPoint> enclosed;
  ClearedPoints cleared;
  FilterTarget target;
};

/// Every point against one double quadric (plane): the filter, then exact
/// integers, then the exact measure, each where the one before is undecided.
/// `passed`, when given, receives one entry per point (1 pass, 0 fail). The
/// item passes when `failed` is 0.
FilterCounts check_quadric_filtered(const FilterPoints& pts, const Mat4<double>& Q, std::vector<char>* passed = nullptr);
FilterCounts check_plane_filtered(const FilterPoints& pts, const Vec4<double>& pi, std::vector<char>* passed = nullptr);

}  // namespace qverify
