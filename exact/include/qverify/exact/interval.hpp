#pragma once
/// \file interval.hpp
/// Certified interval arithmetic as a scalar of the ladder: CGAL's
/// `Interval_nt` (double bounds, rounding mode protected by the class). Every
/// operation returns an interval that contains the exact result, so a result
/// computed from input enclosures encloses the exact result.
///
/// The core's decisions go through ScalarOps; for intervals a comparison holds
/// only when it is *certain* (a.sup < b.inf), and nothing throws. Status words
/// of interval results are taken from the exact twin (eval.hpp).

#include <qverify/core/scalar.hpp>
#include <qverify/exact/scalars.hpp>

#include <CGAL/Interval_nt.h>

#include <cmath>

namespace qverify {

using Interval = CGAL::Interval_nt<true>;

/// The enclosure [round down, round up] of q in double (subnormals included).
Interval enclose(const Rational& q);

/// The midpoint of an interval, exactly (for error measurements).
Rational to_rational(const Interval& x);

}  // namespace qverify

template <bool P> struct qverify::ScalarOps<CGAL::Interval_nt<P>> {
  using S = CGAL::Interval_nt<P>;
  static constexpr bool interval = true;
  static bool exact() { return false; }
  static bool less(const S& a, const S& b) { return a.sup() < b.inf(); }
  static bool is_zero(const S& a) { return a.inf() == 0 && a.sup() == 0; }
  static S abs(const S& x) { return CGAL::abs(x); }
  static bool finite(const S& x) { return std::isfinite(x.inf()) && std::isfinite(x.sup()); }
};

// Batches of intervals run on SIMD packs wherever Interval_nt is known, so that
// every translation unit sees the same BatchLanes specialisation.
#include <qverify/exact/interval_pack.hpp>
